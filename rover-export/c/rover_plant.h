/*
 * rover_plant.h: a rover's plant as a C library (docs/EXPORT.md, "The C API").
 *
 * A plant is created from a scenario file (TOML; the rover and the terrain
 * files it names are found beside it), then stepped: each rover_step
 * advances the scenario's integrator by dt seconds, through the same run
 * as `rover simulate`, with the scenario's own controllers plus the
 * torques, steering angles and spring neutrals set here.
 *
 * Every function but rover_destroy, rover_output_name and
 * rover_error_message returns ROVER_OK, ROVER_ERROR (refused or failed:
 * rover_error_message says why; the plant stays usable, a failed run
 * until rover_reset) or ROVER_UNUSABLE (a null or destroyed plant).
 * Nothing allocates after rover_create except an error's message. Calls
 * on one plant from several threads take turns; plants are independent.
 *
 * Written by hand against rover-export's src/capi.rs and the symbols of
 * rover_export::entry_points!; rover-plant's tests compile it with the
 * example and check that it declares every exported rover_ function.
 */
#ifndef ROVER_PLANT_H
#define ROVER_PLANT_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Done. */
#define ROVER_OK 0
/* Refused or failed; rover_error_message says why. */
#define ROVER_ERROR 1
/* A null or destroyed plant. */
#define ROVER_UNUSABLE 2

/* A plant: one scenario's run. */
typedef struct RoverPlant RoverPlant;

/* Create the plant of the scenario file `scenario_path`. On success
 * *plant is set and ROVER_OK returned; otherwise *plant is NULL and the
 * message (NUL-terminated, truncated to message_size bytes) says which
 * file or field is wrong. `message` may be NULL. */
int rover_create(const char *scenario_path, RoverPlant **plant, char *message, size_t message_size);

/* Destroy the plant. A later call with it returns ROVER_UNUSABLE (the
 * handle's few bytes are kept to tell it apart from a live one). */
void rover_destroy(RoverPlant *plant);

/* Back to t = 0: the initial state, the inputs at zero and the springs'
 * neutrals at the rover's. */
int rover_reset(RoverPlant *plant);

/* Advance by dt seconds (finite, positive). The inputs set since the
 * last step take effect at its start. */
int rover_step(RoverPlant *plant, double dt);

/* Motor torques [N m], one per wheel (the description's order), added to
 * the scenario's own controllers and held until set again. */
int rover_set_torques(RoverPlant *plant, const double *torques, size_t n);

/* Steering angles [rad], one per wheel (0 for a wheel that does not
 * steer), added to the scenario's. */
int rover_set_steering(RoverPlant *plant, const double *angles, size_t n);

/* The springs' neutrals [rad or m], one per suspension coordinate: an
 * active suspension's set-points. */
int rover_set_neutrals(RoverPlant *plant, const double *neutrals, size_t n);

/* The outputs at the current time, `n` = rover_output_count's, in the
 * order of `rover simulate`'s CSV columns (t first). */
int rover_outputs(RoverPlant *plant, double *out, size_t n);

/* The number of outputs, wheels and suspension coordinates. */
int rover_output_count(RoverPlant *plant, size_t *n);
int rover_wheel_count(RoverPlant *plant, size_t *n);
int rover_coordinate_count(RoverPlant *plant, size_t *n);

/* Output i's name (the CSV column's), or NULL past the last. Valid until
 * the plant is destroyed. */
const char *rover_output_name(RoverPlant *plant, size_t i);

/* The current time [s]; the scenario's output interval [s]. */
int rover_time(RoverPlant *plant, double *t);
int rover_output_step(RoverPlant *plant, double *dt);

/* The last error's message ("" when none), valid until the next call on
 * the plant. */
const char *rover_error_message(RoverPlant *plant);

#ifdef __cplusplus
}
#endif

#endif /* ROVER_PLANT_H */
