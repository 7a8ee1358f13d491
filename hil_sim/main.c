/* hil_sim: the HIL simulator command line, on top of its folders: src/ (run, pil), bus/ (serve),
 * faults/ (faults, powercut). Subcommands are a table: add one line to add one. */
#include <stdio.h>
#include <string.h>

#include "fault_powercut.h"
#include "faults.h"
#include "serve.h"
#include "sim_cli.h"
#include "sim_pil.h"

typedef struct {
    const char *name;
    int (*fn)(int argc, char **argv);
    const char *help;
} sim_command_t;

static const sim_command_t COMMANDS[] = {
    {"run", sim_cmd_run, "run a scenario in lockstep, write a CSV log and a JSON summary"},
    {"serve", bus_cmd_serve,
     "run the device firmware in real time, serve its CAN bus (socketcand)"},
    {"pil", sim_cmd_pil,
     "run the product's Cortex-M image under qemu, its UART as a CAN bus (SLCAN)"},
    {"faults", faults_cmd,
     "inject every fault scenario into the device in lockstep, write the table"},
    {"powercut", powercut_cmd,
     "cut the power after every flash operation of a skill download and a firmware update"},
};

static void usage(FILE *f)
{
    fprintf(f, "usage: hil_sim COMMAND [options]   (hil_sim COMMAND --help for its options)\n"
               "HIL simulator of the forceskill device: plant, objects, operator, sensors, with\n"
               "the firmware core in the loop (docs/hil.md).\ncommands:\n");
    for (size_t i = 0; i < sizeof COMMANDS / sizeof COMMANDS[0]; i++) {
        fprintf(f, "  %-8s %s\n", COMMANDS[i].name, COMMANDS[i].help);
    }
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    if (strcmp(argv[1], "-h") == 0 || strcmp(argv[1], "--help") == 0) {
        usage(stdout);
        return 0;
    }
    for (size_t i = 0; i < sizeof COMMANDS / sizeof COMMANDS[0]; i++) {
        if (strcmp(argv[1], COMMANDS[i].name) == 0) {
            return COMMANDS[i].fn(argc - 2, argv + 2);
        }
    }
    fprintf(stderr, "hil_sim: unknown command '%s'\n", argv[1]);
    usage(stderr);
    return 2;
}
