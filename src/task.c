/* Tasks: the name tables generated from TASK_TYPES, TASK_SUBTYPES and the
 * registry of task families. */
#include "src/task.h"

const char *const task_type_names[task_type_count] = {
#define TASK_NAME_(name) #name,
#define TASK_FAMILY_TYPE_X_ TASK_NAME_
    TASK_TYPES(TASK_NAME_)
#undef TASK_FAMILY_TYPE_X_
#undef TASK_NAME_
};

const char *const task_subtype_names[task_subtype_count] = {
#define TASK_NAME_(name) #name,
#define TASK_FAMILY_SUBTYPE_X_ TASK_NAME_
    TASK_SUBTYPES(TASK_NAME_)
#undef TASK_FAMILY_SUBTYPE_X_
#undef TASK_NAME_
};

const char *const task_family_names[task_family_count] = {
#define TASK_NAME_(name, subtype, policy, place, gpu, when, stage, reads, writes) #name,
    TASK_FAMILIES(TASK_NAME_)
#undef TASK_NAME_
};

int task_lock(struct task *t) {
  struct sched_lock *a = t->locks[0], *b = t->locks[1];
  if (b == a) b = NULL; /* the same resource twice: one lock */
  if (a && !sched_lock_try(a)) return 0;
  if (b && !sched_lock_try(b)) {
    if (a) sched_lock_release(a);
    return 0;
  }
  return 1;
}

void task_unlock(struct task *t) {
  if (t->locks[0]) sched_lock_release(t->locks[0]);
  if (t->locks[1] && t->locks[1] != t->locks[0]) sched_lock_release(t->locks[1]);
}
