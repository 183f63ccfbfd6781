/* CPU against GPU on the same particles, every task family of the FORCE
 * phase (STYLE.md rule 9): density sums (rho, neighbour number, div v), the
 * iterated smoothing lengths, pressure and sound speed from the EOS, the
 * accelerations, du/dt, the signal velocity, the kicked velocities and
 * energies and the new time steps.  The CPU side runs the engine's task
 * functions cell by cell (symmetric self and pair loops, ghost, kick2); the
 * GPU side runs the runner's FORCE phase (gather form, one thread per
 * particle).  The two differ only in the order of the sums, so every
 * quantity must agree to 1e-10 relative (measured: ~1e-14).
 * Two cases: a periodic box of ideal gas and an open box of Tillotson
 * granite (material library), both jittered lattices with h off by up to
 * 40% so that the h iteration runs several rounds.  Exits 77 (skip) when
 * there is no CUDA device. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "density/density_cpu.h"
#include "engine.h"
#include "error.h"
#include "force/force_cpu.h"
#include "ghost/ghost_cpu.h"
#include "gpu/gpu_engine.h"
#include "hydro_parts.h"
#include "kernel.h"
#include "kick/kick_cpu.h"
#include "material.h"
#include "space.h"

/** Uniform random number in [0, 1) (64-bit LCG). */
static double urand(unsigned long long *s) {
  *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
  return (double)(*s >> 11) * (1.0 / 9007199254740992.0);
}

/** Per-top-cell neighbour lists as the engine builds them (engine_graph.c). */
static struct engine_cell_tasks *make_ngbs(const struct space *s) {
  struct engine_cell_tasks *ct = calloc(s->nr_top, sizeof *ct);
  const double zero[3] = {0, 0, 0};
  struct space_pair *pairs;
  const size_t np = space_top_pairs(s, &pairs);
  for (int c = 0; c < s->nr_top; c++) {
    ct[c].ngb = malloc((27 + 2) * sizeof(int));
    ct[c].ngb_shift = malloc((27 + 2) * sizeof(double[3]));
    ct[c].ngb[0] = c;
    memcpy(ct[c].ngb_shift[0], zero, sizeof zero);
    ct[c].nr_ngb = 1;
  }
  for (size_t k = 0; k < np; k++) {
    const int a = pairs[k].ci, b = pairs[k].cj;
    ct[a].ngb[ct[a].nr_ngb] = b;
    ct[b].ngb[ct[b].nr_ngb] = a;
    for (int d = 0; d < 3; d++) {
      ct[a].ngb_shift[ct[a].nr_ngb][d] = pairs[k].shift[d];
      ct[b].ngb_shift[ct[b].nr_ngb][d] = -pairs[k].shift[d];
    }
    ct[a].nr_ngb++;
    ct[b].nr_ngb++;
  }
  free(pairs);
  return ct;
}

/** Largest |a - b| / scale over the particles, scale from the reference. */
static double worst_rel(const double *a, const double *b, size_t n, double floor) {
  double w = 0.0;
  for (size_t i = 0; i < n; i++) {
    const double e = fabs(a[i] - b[i]) / (fabs(b[i]) + floor);
    if (e > w) w = e;
  }
  return w;
}

/** One case: returns the number of failed comparisons. */
static int run_case(struct gpu *g, int periodic, int side, int granite, unsigned long long seed) {
  unsigned long long s = seed;
  const size_t n = (size_t)side * side * side;
  const double box[3] = {1.0, 1.0, 1.0};
  const double dx = (periodic ? 1.0 : 0.6) / side, rho0 = granite ? 2680.0 : 1.0;
  struct parts p;
  parts_alloc(&p, n);
  struct hydro_props hp = {.enabled = 1,
                           .eta = 1.2348,
                           .h_tolerance = 1e-4,
                           .h_max = 1.0,
                           .max_iterations = 60,
                           .cfl = 0.2,
                           .log_max_volume_change = log(1.4),
                           .alpha = 1.5,
                           .beta = 3.0,
                           .balsara = 1,
                           .alpha_u = 0.5};
  size_t i = 0;
  for (int a = 0; a < side; a++)
    for (int b = 0; b < side; b++)
      for (int c = 0; c < side; c++, i++) {
        const double o = periodic ? 0.0 : 0.2;
        p.x[i] = o + (a + 0.5 + 0.3 * (urand(&s) - 0.5)) * dx;
        p.y[i] = o + (b + 0.5 + 0.3 * (urand(&s) - 0.5)) * dx;
        p.z[i] = o + (c + 0.5 + 0.3 * (urand(&s) - 0.5)) * dx;
        p.vx[i] = p.vpx[i] = 0.3 * sin(6.283 * p.y[i]) + 0.1 * (urand(&s) - 0.5);
        p.vy[i] = p.vpy[i] = 0.3 * cos(6.283 * p.z[i]) + 0.1 * (urand(&s) - 0.5);
        p.vz[i] = p.vpz[i] = 0.1 * (urand(&s) - 0.5);
        p.m[i] = rho0 * dx * dx * dx * (0.8 + 0.4 * urand(&s));
        p.h[i] = hp.eta * dx * (0.7 + 0.7 * urand(&s));
        p.u[i] = p.up[i] = (granite ? 1e6 : 1.0) * (0.5 + urand(&s));
        p.mat[i] = granite ? 1 : 0;
        p.id[i] = (int64_t)i;
      }
  struct material_table mats;
  material_table_init(&mats);
  struct material m;
  char msg[256];
  if (granite) {
    material_from_library(&m, material_default_library(), "granite", 1);
  } else {
    material_init(&m, 0, "gas", EOS_IDEAL_GAS);
    material_set(&m, "gamma", 5.0 / 3.0, msg, sizeof msg);
  }
  if (material_finalize(&m, msg, sizeof msg)) error_exit("%s", msg);
  material_table_add(&mats, &m);

  struct space sp;
  space_init(&sp, &p, box, periodic, 64, 4);
  space_rebuild(&sp);
  struct engine_cell_tasks *ct = make_ngbs(&sp);
  /* the top-level cells serve as task cells */
  struct cell **tcells = malloc(sp.nr_top * sizeof(struct cell *));
  for (int c = 0; c < sp.nr_top; c++) tcells[c] = &sp.cells[c];
  struct space_pair *pairs;
  const size_t np = space_top_pairs(&sp, &pairs);
  double H_limit = sp.width[0];
  for (int k = 0; k < 3; k++) {
    if (sp.width[k] < H_limit) H_limit = sp.width[k];
    if (periodic && 0.5 * sp.dim[k] < H_limit) H_limit = 0.5 * sp.dim[k];
  }
  double *top_h_cap = malloc(sp.nr_top * sizeof(double));
  for (int c = 0; c < sp.nr_top; c++)
    top_h_cap[c] = (H_limit - 2.0 * sp.cells[c].dx_max) / kernel_gamma;

  /* the GPU copy, taken before the CPU touches anything */
  struct parts q;
  parts_alloc(&q, n);
  for (int f = 0; f < part_nr_fields; f++)
    memcpy(part_field_array(&q, &part_fields[f]), part_field_array(&p, &part_fields[f]),
           n * part_fields[f].size);
  const double dt_kick = 1e-3;

  /* CPU: the engine's tasks, cell by cell */
  double t0 = error_walltime();
  for (size_t k = 0; k < n; k++) hydro_density_reset(&p, k);
  for (int c = 0; c < sp.nr_top; c++) density_self_cpu(&p, &sp.cells[c]);
  for (size_t k = 0; k < np; k++)
    density_pair_cpu(&p, &sp.cells[pairs[k].ci], &sp.cells[pairs[k].cj], pairs[k].shift);
  int capped_cpu = 0;
  for (int c = 0; c < sp.nr_top; c++) {
    struct cell *cells[32];
    for (int k = 0; k < ct[c].nr_ngb; k++) cells[k] = &sp.cells[ct[c].ngb[k]];
    struct ghost_ngbs ng = {ct[c].nr_ngb, cells, (const double(*)[3])ct[c].ngb_shift};
    capped_cpu |= ghost_cell_cpu(&p, &sp.cells[c], &ng, &hp, &mats, top_h_cap[c] * kernel_gamma);
  }
  for (int c = 0; c < sp.nr_top; c++) force_self_cpu(&p, &sp.cells[c], &hp);
  for (size_t k = 0; k < np; k++)
    force_pair_cpu(&p, &sp.cells[pairs[k].ci], &sp.cells[pairs[k].cj], pairs[k].shift, &hp);
  double *dt_cpu = malloc(sp.nr_top * sizeof(double)), *dt_gpu = malloc(sp.nr_top * sizeof(double));
  for (int c = 0; c < sp.nr_top; c++)
    dt_cpu[c] = sp.cells[c].count ? kick2_cell_cpu(&p, &sp.cells[c], dt_kick, &hp) : 1e300;
  const double t_cpu = error_walltime() - t0;

  /* GPU: the runner's FORCE phase on the copy, cells reset to its h */
  sp.parts = &q;
  for (int c = 0; c < sp.nr_top; c++) cell_update_bounds(&q, &sp.cells[c]);
  struct gpu_cells gc;
  memset(&gc, 0, sizeof gc);
  gc.nr_threads = 3; /* the threaded list build */
  t0 = error_walltime();
  const int capped_gpu = gpu_cells_force(g, &gc, &q, &sp, tcells, sp.nr_top, ct, top_h_cap, &hp,
                                         &mats, dt_kick, 0, dt_gpu);
  const double t_gpu = error_walltime() - t0;

  /* compare */
  double amax = 0.0, hmean = 0.0;
  for (size_t k = 0; k < n; k++) {
    amax = fmax(amax, sqrt(p.ax[k] * p.ax[k] + p.ay[k] * p.ay[k] + p.az[k] * p.az[k]));
    hmean += p.h[k] / n;
  }
  double vmax = 0.0, umax = 0.0, dumax = 0.0;
  for (size_t k = 0; k < n; k++) {
    vmax = fmax(vmax, fabs(p.vx[k]));
    umax = fmax(umax, fabs(p.u[k]));
    dumax = fmax(dumax, fabs(p.du_dt[k]));
  }
  struct {
    const char *name;
    const double *cpu, *gpu;
    double floor;
  } cmp[] = {
      {"rho", p.rho, q.rho, 0.0},
      {"wcount", p.wcount, q.wcount, 0.0},
      {"h", p.h, q.h, 0.0},
      {"div_v", p.div_v, q.div_v, 1e-3 * vmax / hmean},
      {"P", p.P, q.P, 1e-12 * umax * rho0},
      {"cs", p.cs, q.cs, 0.0},
      {"ax", p.ax, q.ax, amax},
      {"ay", p.ay, q.ay, amax},
      {"az", p.az, q.az, amax},
      {"du_dt", p.du_dt, q.du_dt, dumax},
      {"v_sig", p.v_sig, q.v_sig, 0.0},
      {"vx", p.vx, q.vx, vmax},
      {"u", p.u, q.u, 0.0},
  };
  int fail = 0;
  printf(
      "%s box, %zu particles, %s: CPU %.3f s (1 thread), GPU %.3f s (lists %d leaves, %d "
      "entries)\n",
      periodic ? "periodic" : "open", n, granite ? "Tillotson granite" : "ideal gas", t_cpu, t_gpu,
      gc.n, gc.nr_ngb);
  for (size_t k = 0; k < sizeof cmp / sizeof cmp[0]; k++) {
    const double w = worst_rel(cmp[k].gpu, cmp[k].cpu, n, cmp[k].floor);
    const int bad = !(w < 1e-10);
    printf("  %-7s worst relative difference %.3e%s\n", cmp[k].name, w,
           bad ? "  FAIL (> 1e-10)" : "");
    fail += bad;
  }
  const double wdt = worst_rel(dt_gpu, dt_cpu, (size_t)sp.nr_top, 0.0);
  printf("  %-7s worst relative difference %.3e%s\n", "dt", wdt,
         wdt < 1e-10 ? "" : "  FAIL (> 1e-10)");
  fail += !(wdt < 1e-10);
  if (capped_cpu != capped_gpu) {
    printf("  FAIL: capped by the cells: CPU %d, GPU %d\n", capped_cpu, capped_gpu);
    fail++;
  }
  gpu_cells_free(&gc);
  for (int c = 0; c < sp.nr_top; c++) {
    free(ct[c].ngb);
    free(ct[c].ngb_shift);
  }
  free(ct);
  free(pairs);
  free(top_h_cap);
  free(tcells);
  free(dt_cpu);
  free(dt_gpu);
  space_free(&sp);
  parts_free(&p);
  parts_free(&q);
  material_table_free(&mats);
  return fail;
}

int main(int argc, char **argv) {
  (void)argc;
  error_init(argv[0]);
  char why[256];
  struct gpu *g = gpu_init(why, sizeof why);
  if (!g) {
    printf("SKIP: no GPU (%s)\n", why);
    return 77;
  }
  printf("device: %s\n", gpu_name(g));
  int fail = 0;
  fail += run_case(g, 1, 24, 0, 12345);
  fail += run_case(g, 0, 20, 1, 777);
  gpu_print_timers(g, stdout);
  gpu_free(g);
  printf("%s\n", fail ? "FAIL" : "PASS");
  return fail ? 1 : 0;
}
