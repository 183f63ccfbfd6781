/* The scheduler's callback: what each task of the engine's graph does.  The
 * function of each kind of task (type, subtype) comes from the registry of
 * task families (tasks/task_families.h); the engine knows no family here. */
#include "src/engine_tasks.h"
#include "src/error.h"

/** The largest kernel support the current cells and task graph allow. */
double engine_H_limit(const struct engine *e) {
  const struct space *s = &e->space;
  double w = e->reach;
  if (s->periodic)
    for (int k = 0; k < 3; k++)
      if (0.5 * s->dim[k] < w) w = 0.5 * s->dim[k];
  return w;
}

/** The CPU function of each (type, subtype), from the registry; NULL: no
 *  family makes such a task. */
static void (*const engine_task_cpu[task_type_count][task_subtype_count])(struct engine *,
                                                                          struct task *) = {
#define ENGINE_TASK_CPU_(family, shape, type, subtype, cpu) \
  [task_type_##type][task_subtype_##subtype] = cpu,
    TASK_FAMILY_TASKS(ENGINE_TASK_CPU_)
#undef ENGINE_TASK_CPU_
};

void engine_run_task(void *ctx, struct task *t, int thread_id) {
  (void)thread_id;
  if (t->type == task_type_implicit) return; /* only dependencies */
  void (*const fn)(struct engine *, struct task *) = engine_task_cpu[t->type][t->subtype];
  if (!fn)
    error_bug("the engine has no work for task type %s/%s", task_type_names[t->type],
              task_subtype_names[t->subtype]);
  fn(ctx, t);
}
