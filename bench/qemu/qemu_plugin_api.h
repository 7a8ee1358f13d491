/* The few declarations of QEMU's TCG plugin API (the C interface of include/qemu/qemu-plugin.h,
 * plugin API version 1, as in QEMU 7.2) that bench/qemu/tick_plugin.c uses, written here so that
 * the bench builds with the host's cc alone. qemu resolves these functions in its own executable
 * when it loads the plugin (-plugin file=X.so,...); a plugin declares the API version it follows
 * in qemu_plugin_version, and qemu refuses one outside its [min, cur] range. */
#ifndef BENCH_QEMU_PLUGIN_API_H
#define BENCH_QEMU_PLUGIN_API_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define QEMU_PLUGIN_EXPORT __attribute__((visibility("default")))
#define QEMU_PLUGIN_API_VERSION 1 /* the version these declarations follow */

/* A plugin's handle, given to qemu_plugin_install. */
typedef uint64_t qemu_plugin_id_t;

/* What qemu tells the plugin at install time. */
typedef struct qemu_info_t {
    const char *target_name; /* the guest architecture ("arm") */
    struct {
        int min; /* the oldest API version qemu accepts */
        int cur; /* qemu's API version */
    } version;
    bool system_emulation; /* softmmu (qemu-system-*) rather than user mode */
    union {
        struct {
            int smp_vcpus;
            int max_vcpus;
        } system;
    };
} qemu_info_t;

/* A translation block and one of its instructions, valid during the translation callback only. */
struct qemu_plugin_tb;
struct qemu_plugin_insn;

/* Which guest registers a callback may read or write (none here). */
enum qemu_plugin_cb_flags {
    QEMU_PLUGIN_CB_NO_REGS,
    QEMU_PLUGIN_CB_R_REGS,
    QEMU_PLUGIN_CB_RW_REGS,
};

typedef void (*qemu_plugin_udata_cb_t)(qemu_plugin_id_t id, void *userdata);
typedef void (*qemu_plugin_vcpu_udata_cb_t)(unsigned int vcpu_index, void *userdata);
typedef void (*qemu_plugin_vcpu_tb_trans_cb_t)(qemu_plugin_id_t id, struct qemu_plugin_tb *tb);

/* The plugin's entry point: 0 when installed, else qemu refuses to start. */
QEMU_PLUGIN_EXPORT int qemu_plugin_install(qemu_plugin_id_t id, const qemu_info_t *info, int argc,
                                           char **argv);

/* Call cb for each translation block qemu translates. */
void qemu_plugin_register_vcpu_tb_trans_cb(qemu_plugin_id_t id, qemu_plugin_vcpu_tb_trans_cb_t cb);
/* Call cb (with userdata) each time insn is about to execute. */
void qemu_plugin_register_vcpu_insn_exec_cb(struct qemu_plugin_insn *insn,
                                            qemu_plugin_vcpu_udata_cb_t cb,
                                            enum qemu_plugin_cb_flags flags, void *userdata);
/* Call cb at qemu's exit. */
void qemu_plugin_register_atexit_cb(qemu_plugin_id_t id, qemu_plugin_udata_cb_t cb, void *userdata);
/* The number of instructions of tb and the idx-th of them. */
size_t qemu_plugin_tb_n_insns(const struct qemu_plugin_tb *tb);
struct qemu_plugin_insn *qemu_plugin_tb_get_insn(const struct qemu_plugin_tb *tb, size_t idx);
/* The guest address of insn and the name of the ELF symbol it lies in (NULL if none). */
uint64_t qemu_plugin_insn_vaddr(const struct qemu_plugin_insn *insn);
const char *qemu_plugin_insn_symbol(const struct qemu_plugin_insn *insn);
/* The bytes of insn (qemu_plugin_insn_size of them, in guest memory order). */
const void *qemu_plugin_insn_data(const struct qemu_plugin_insn *insn);
size_t qemu_plugin_insn_size(const struct qemu_plugin_insn *insn);

#endif
