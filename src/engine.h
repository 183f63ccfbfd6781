/* The engine: the time-step loop (rebuild, build the task graph, run it,
 * output). */
#ifndef BOLIDE_ENGINE_H
#define BOLIDE_ENGINE_H
#endif
