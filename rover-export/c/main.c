/*
 * Drive the exported rover for 10 s with the scenario's own controllers
 * and print its final state, one "name value" line per output.
 *
 *   cc -O2 -I. main.c librover_plant.a -lgcc_s -lutil -lrt -lpthread -lm -ldl -lc -o rover_main
 *   ./rover_main [scenario/scenario.toml]
 */
#include <stdio.h>
#include <stdlib.h>

#include "rover_plant.h"

int main(int argc, char **argv) {
    const char *scenario = argc > 1 ? argv[1] : "scenario/scenario.toml";
    char message[1024];
    RoverPlant *plant = NULL;
    if (rover_create(scenario, &plant, message, sizeof message) != ROVER_OK) {
        fprintf(stderr, "rover_create: %s\n", message);
        return 2;
    }
    size_t n = 0, wheels = 0;
    rover_output_count(plant, &n);
    rover_wheel_count(plant, &wheels);
    double *out = malloc(n * sizeof *out);
    double *torques = calloc(wheels, sizeof *torques);
    double dt = 0.0, t = 0.0;
    rover_output_step(plant, &dt);

    /* A rig's controller would set its torques here, each step; zero
     * leaves the scenario's own controllers in charge. */
    rover_set_torques(plant, torques, wheels);
    /* Whole output intervals, as `rover simulate` writes its rows. */
    long steps = (long)(10.0 / dt + 0.5);
    for (long k = 0; k < steps; k++) {
        if (rover_step(plant, dt) != ROVER_OK) {
            fprintf(stderr, "rover_step: %s\n", rover_error_message(plant));
            rover_destroy(plant);
            return 1;
        }
    }
    rover_time(plant, &t);
    rover_outputs(plant, out, n);
    for (size_t i = 0; i < n; i++) {
        printf("%s %.17g\n", rover_output_name(plant, i), out[i]);
    }
    free(out);
    free(torques);
    rover_destroy(plant);
    return 0;
}
