/* Scheduler:gpu (gpu_policy.h). */
#include "src/gpu/gpu_policy.h"

#include <ctype.h>
#include <stdio.h>
#include <string.h>

/** Append the names of the families in mask to buf as "a, b, c". */
static void gpu_policy_names(unsigned mask, char *buf, size_t len) {
  buf[0] = '\0';
  for (int f = 0; f < task_family_count; f++)
    if (mask & (1u << f)) {
      const size_t n = strlen(buf);
      snprintf(buf + n, len - n, "%s%s", n ? ", " : "", task_family_names[f]);
    }
}

struct gpu_policy gpu_policy_read(const struct params *p) {
  const char *key = "Scheduler:gpu";
  struct gpu_policy pol;
  memset(&pol, 0, sizeof pol);
  const char *v = params_get_string(p, key);
  snprintf(pol.text, sizeof pol.text, "%s", v);
  if (strcmp(v, "auto") == 0) {
    pol.kind = GPU_POLICY_AUTO;
    return pol;
  }
  if (strcmp(v, "off") == 0) {
    pol.kind = GPU_POLICY_OFF;
    return pol;
  }
  if (strcmp(v, "all") == 0) {
    pol.kind = GPU_POLICY_ALL;
    return pol;
  }
  /* a list: "[a, b]" (a YAML sequence) or "a, b" / "a b" (a -P value) */
  pol.kind = GPU_POLICY_LIST;
  const char *c = v;
  while (isspace((unsigned char)*c)) c++;
  const int bracket = *c == '[';
  if (bracket) c++;
  char known[256];
  gpu_policy_names(TASK_FAMILIES_GPU, known, sizeof known);
  for (;;) {
    while (isspace((unsigned char)*c) || *c == ',') c++;
    if (*c == '\0' || (bracket && *c == ']')) break;
    const size_t n = strcspn(c, ", \t\n]");
    int f = 0;
    while (f < task_family_count &&
           (!(TASK_FAMILIES_GPU & (1u << f)) || strlen(task_family_names[f]) != n ||
            strncmp(task_family_names[f], c, n) != 0))
      f++;
    if (f == task_family_count)
      params_error(p, key, "'%.*s' is not a task family: expected auto, off, all or a list of %s",
                   (int)n, c, known);
    pol.families |= 1u << f;
    c += n;
  }
  if (bracket && *c != ']') params_error(p, key, "the list '%s' lacks its closing ']'", v);
  if (bracket && c[1 + strspn(c + 1, " \t")] != '\0')
    params_error(p, key, "text after the list '%s'", v);
  const unsigned hydro = TASK_FAMILIES_HYDRO;
  if (pol.families && (pol.families & hydro) != hydro) {
    char missing[256];
    gpu_policy_names(hydro & ~pol.families, missing, sizeof missing);
    params_error(p, key,
                 "the hydrodynamic families run on the GPU as one phase (with the particles "
                 "resident there): the list lacks %s",
                 missing);
  }
  return pol;
}
