/* tick_plugin.c: the exact instruction counter of bench/qemu_tick.sh as a qemu TCG plugin (the
 * plugin API of bench/qemu/qemu_plugin_api.h: QEMU's include/qemu/qemu-plugin.h, version 1).
 *
 * qemu translates blocks of many instructions (normal chaining, no one-instruction-per-block) and
 * calls on_insn before each instruction it executes, with the instruction's ELF symbol
 * (qemu_plugin_insn_symbol, the name `-d exec` prints). The callback runs inside the block, after
 * the block's entry check, so an instruction counts once when it executes: not when qemu enters a
 * block only to leave it for an interrupt or the end of the instruction budget (-icount), and
 * not twice when qemu re-executes a block's I/O instruction alone (its recompiled block calls no
 * instruction callback). Interrupts are taken between blocks: the handler's instructions follow
 * the interrupted one's as in the one-instruction trace.
 *
 * On this stream of symbols the plugin runs the accounting of bench/qemu_tick.sh's trace counter
 * (COUNT_AWK there, the same rules line for line) and writes the same lines to out=FILE:
 *   KIND app_tick part stepped dmp commit act  per counted tick (cm_port_mark_begin .. _end, then
 *                                           cm_port_mark_KIND; act: the instructions up to
 *                                           hal_actuator_force's first, 0 without one)
 *   boot total app_init                     per boot (Reset_Handler to the first counted tick)
 *   check total ticks max_per_tick          per skill check (skchk_*)
 *   softfloat KIND helper calls instructions  at exit, per kind and soft-float helper
 *   isr_lost N                              at exit, if the interrupt tracking missed N entries
 *                                           or returns (never expected)
 * mode=count instead writes, per region of cm_count_check, the instructions between
 * cm_port_mark_begin and cm_port_mark_end (the counter check's calibration).
 * log=FILE also writes every executed instruction there ("pc symbol", the exactness check's
 * stream: bench/qemu_tick.sh compares it with the one-instruction trace's).
 * limit=N stops counting after N instructions (out then ends with "limit N").
 * prof=PREFIX (focus=ERE) also writes the profiles of bench/qemu_tick.sh's QEMU_TICK_PROFILE=PREFIX
 * (QEMU_TICK_FOCUS=ERE) at exit, the files COUNT_AWK writes.
 * Arguments (key=value): out=FILE, mode=ticks|count, log=FILE, limit=N, prof=PREFIX, focus=ERE,
 * dmp=ERE, law=NAME, commit=ERE, softf=ERE, chk=ERE (POSIX extended regular expressions, searched in the symbol name as awk's
 * `s ~ RE`; an absent one matches nothing). */
#define _POSIX_C_SOURCE 200809L /* strdup */
#include "qemu_plugin_api.h"

#include <regex.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

QEMU_PLUGIN_EXPORT int qemu_plugin_version = QEMU_PLUGIN_API_VERSION;

#define MAX_SYMS 16384u      /* distinct symbol names (more fold into the last one) */
#define INSN_HASH (1u << 20) /* instruction addresses seen (open addressing) */
#define N_KINDS 7

enum {
    F_BEGIN = 1u << 0,
    F_END = 1u << 1,
    F_RESET = 1u << 2,
    F_HANDLER = 1u << 3, /* *_Handler but Reset_Handler */
    F_APPINIT = 1u << 4,
    F_DMP = 1u << 5,
    F_LAW = 1u << 6,
    F_COMMIT = 1u << 7,
    F_SOFTF = 1u << 8,
    F_CHK = 1u << 9,
    F_ACT = 1u << 10, /* hal_actuator_force: the tick's actuator write */
};

static const char *const KIND_NAMES[N_KINDS] = {"idle",     "teach", "execute", "upload",
                                                "fwupdate", "fault", "other"};

typedef struct {
    char *name;
    uint32_t flags;
    int kind; /* cm_port_mark_KIND: its index, else -1 */
} sym_t;

/* An instruction's control transfer, as the interrupt tracking needs it. */
enum {
    I_OTHER,
    I_CALL,
    I_RET
};

typedef struct {
    uint64_t addr;
    uint64_t hp, tp; /* prof=: its executions in the current tick, summed over EXECUTE ticks */
    int32_t sym;
    uint8_t size; /* bytes */
    uint8_t xfer; /* I_CALL (bl, blx), I_RET (bx lr, pop/ldm/ldr of pc from the stack) or I_OTHER */
    uint8_t used;
} insn_t;

static sym_t g_syms[MAX_SYMS];
static uint32_t g_n_syms;
static insn_t *g_insns; /* INSN_HASH entries */
static FILE *g_out;
static FILE *g_log;                    /* log=FILE: every executed instruction, "pc symbol" */
static uint64_t g_limit, g_n_executed; /* limit=N: stop after N instructions (0: never) */
static int g_count_mode;
typedef struct {
    regex_t re;
    int set;
} ere_t;
static ere_t g_re_dmp, g_re_commit, g_re_softf, g_re_chk;
static const char *g_law = "";

/* The accounting's state: the variables of COUNT_AWK (-1: the empty symbol). */
typedef struct {
    int inb, done, inboot, ininit, inpart, indmp, inisr, inchk, dmp, cmt;
    uint64_t c, part, dpart, bc, ba, lc, lp, ld, ldp, lcm, act, la;
    uint64_t chk_total, chk_tick, chk_ticks, chk_max;
    int32_t prev, last, bprev, initcaller, caller, dcaller, chkcaller;
} acct_t;

/* The interrupts taken inside a tick: the calls made by their code (return addresses) and, per
 * nested exception, how many of them were open when it was taken. */
#define ISR_DEPTH 64
static uint64_t g_isr_calls[ISR_DEPTH];
static uint32_t g_n_isr_calls;
static uint32_t g_isr_base[ISR_DEPTH], g_n_isr;
static const insn_t *g_prev_insn; /* the instruction executed before the current one */
static uint64_t g_isr_lost; /* interrupts missed (open at a tick's end, a handler's code outside
                               one) or stacks overflowed: 0 */

static acct_t g_a = {.prev = -1,
                     .last = -1,
                     .bprev = -1,
                     .initcaller = -1,
                     .caller = -1,
                     .dcaller = -1,
                     .chkcaller = -1};

/* The soft-float helpers of the current tick (sfi, sfc) and their sums per kind. */
static uint64_t g_sfi[MAX_SYMS], g_sfc[MAX_SYMS];
static uint32_t g_sf_touched[MAX_SYMS], g_n_sf_touched;
static uint64_t g_SFI[N_KINDS][MAX_SYMS], g_SFC[N_KINDS][MAX_SYMS];

/* 1 if re is set and matches in name (awk's name ~ re). */
static int re_match(const ere_t *re, const char *name)
{
    return re->set && regexec(&re->re, name, 0, NULL, 0) == 0;
}

static uint32_t sym_flags(const char *name, int *kind)
{
    static const char MARK[] = "cm_port_mark_";
    uint32_t f = 0;
    const size_t n = strlen(name);
    *kind = -1;
    if (strncmp(name, MARK, sizeof MARK - 1) == 0) {
        for (int k = 0; k < N_KINDS; k++) {
            if (strcmp(name + sizeof MARK - 1, KIND_NAMES[k]) == 0) {
                *kind = k;
            }
        }
    }
    f |= strcmp(name, "cm_port_mark_begin") == 0 ? F_BEGIN : 0u;
    f |= strcmp(name, "cm_port_mark_end") == 0 ? F_END : 0u;
    f |= strcmp(name, "Reset_Handler") == 0 ? F_RESET : 0u;
    if (n >= 8 && strcmp(name + n - 8, "_Handler") == 0 && !(f & F_RESET)) {
        f |= F_HANDLER;
    }
    f |= strcmp(name, "app_init") == 0 ? F_APPINIT : 0u;
    f |= re_match(&g_re_dmp, name) ? F_DMP : 0u;
    f |= strcmp(name, g_law) == 0 ? F_LAW : 0u;
    f |= re_match(&g_re_commit, name) ? F_COMMIT : 0u;
    f |= re_match(&g_re_softf, name) ? F_SOFTF : 0u;
    f |= re_match(&g_re_chk, name) ? F_CHK : 0u;
    f |= strcmp(name, "hal_actuator_force") == 0 ? F_ACT : 0u;
    return f;
}

/* The id of name (interned at its first sight). */
static int32_t sym_id(const char *name)
{
    for (uint32_t i = 0; i < g_n_syms; i++) {
        if (strcmp(g_syms[i].name, name) == 0) {
            return (int32_t)i;
        }
    }
    if (g_n_syms == MAX_SYMS) {
        return (int32_t)(MAX_SYMS - 1u);
    }
    sym_t *s = &g_syms[g_n_syms];
    s->name = strdup(name);
    s->flags = sym_flags(name, &s->kind);
    return (int32_t)g_n_syms++;
}

/* Thumb-2: bl, blx Rm -> I_CALL; bx lr, pop {..pc}, pop.w {..pc}, ldr pc, [sp], #4 -> I_RET (an
 * exception return is one of them, reached with no call of the handler's code open). */
static uint8_t insn_xfer(const uint8_t *d, size_t n)
{
    const unsigned h1 = (unsigned)d[0] | ((unsigned)d[1] << 8);
    if (n == 2u) {
        if ((h1 & 0xFF87u) == 0x4780u) {
            return I_CALL;
        }
        return (h1 == 0x4770u || (h1 & 0xFF00u) == 0xBD00u) ? (uint8_t)I_RET : (uint8_t)I_OTHER;
    }
    const unsigned h2 = n == 4u ? (unsigned)d[2] | ((unsigned)d[3] << 8) : 0u;
    if (n == 4u && (h1 & 0xF800u) == 0xF000u && (h2 & 0xD000u) == 0xD000u) {
        return I_CALL;
    }
    if (n == 4u && ((h1 == 0xE8BDu && (h2 & 0x8000u)) || (h1 == 0xF85Du && h2 == 0xFB04u))) {
        return I_RET;
    }
    return I_OTHER;
}

/* The record of the instruction at addr (its symbol looked up at its first translation). */
static insn_t *insn_at(uint64_t addr, const struct qemu_plugin_insn *insn)
{
    uint32_t h = (uint32_t)((addr >> 1) * 2654435761u) & (INSN_HASH - 1u);
    while (g_insns[h].used && g_insns[h].addr != addr) {
        h = (h + 1u) & (INSN_HASH - 1u);
    }
    insn_t *r = &g_insns[h];
    if (!r->used) {
        char unnamed[32];
        const char *name = qemu_plugin_insn_symbol(insn);
        if (name == NULL || name[0] == '\0') {
            snprintf(unnamed, sizeof unnamed, "[%08llx]", (unsigned long long)addr);
            name = unnamed;
        }
        const size_t n = qemu_plugin_insn_size(insn);
        r->used = 1;
        r->addr = addr;
        r->size = (uint8_t)n;
        r->xfer = n <= 4u ? insn_xfer(qemu_plugin_insn_data(insn), n) : (uint8_t)I_OTHER;
        r->sym = sym_id(name);
    }
    return r;
}

/* prof=PREFIX: the profiles of COUNT_AWK's QEMU_TICK_PROFILE=PREFIX (the same files, the same
 * rules): per function, the instructions of the current tick (h; cleared with the soft-float
 * counts at a kind's mark), their sums over EXECUTE ticks, and the copies of h kept for the tick
 * of each kind with the most / the fewest instructions, for the EXECUTE tick with the largest
 * DMP part and, with focus=ERE, for the tick of each kind whose matching functions ran most. */
typedef struct {
    uint32_t n;
    uint32_t sym[MAX_SYMS];
    uint64_t cnt[MAX_SYMS];
} snap_t;
static const char *g_prof;
static ere_t g_re_focus;
static uint64_t g_h[MAX_SYMS], g_tot[MAX_SYMS], g_nexec;
static uint32_t g_h_touched[MAX_SYMS], g_n_h;
static insn_t **g_hp_touched; /* INSN_HASH entries, with prof= */
static uint32_t g_n_hp;
static snap_t g_hm, g_hk[N_KINDS], g_hf[N_KINDS], g_hn[N_KINDS];
static uint64_t g_maxdp, g_kmax[N_KINDS], g_fmax[N_KINDS], g_kmin[N_KINDS];
static int g_kmin_set[N_KINDS];

/* One instruction of a counted tick into h and hp. */
static void prof_insn(insn_t *cur)
{
    const uint32_t s = (uint32_t)cur->sym;
    if (g_h[s]++ == 0u) {
        g_h_touched[g_n_h++] = s;
    }
    if (cur->hp++ == 0u && g_n_hp < INSN_HASH) {
        g_hp_touched[g_n_hp++] = cur;
    }
}

/* h (only the functions matching focus= if only_focus) into snap. */
static void prof_snap(snap_t *snap, int only_focus)
{
    snap->n = 0;
    for (uint32_t i = 0; i < g_n_h; i++) {
        const uint32_t s = g_h_touched[i];
        if (!only_focus || re_match(&g_re_focus, g_syms[s].name)) {
            snap->sym[snap->n] = s;
            snap->cnt[snap->n++] = g_h[s];
        }
    }
}

/* The tick of kind k just ended (lc instructions, ld: it stepped the DMP, ldp: its DMP part). */
static void prof_tick(int k, uint64_t lc, uint64_t ld, uint64_t ldp)
{
    if (strcmp(KIND_NAMES[k], "execute") == 0) {
        for (uint32_t i = 0; i < g_n_h; i++) {
            g_tot[g_h_touched[i]] += g_h[g_h_touched[i]];
        }
        g_nexec++;
        for (uint32_t i = 0; i < g_n_hp; i++) {
            g_hp_touched[i]->tp += g_hp_touched[i]->hp;
        }
        if (ld && ldp > g_maxdp) {
            g_maxdp = ldp;
            prof_snap(&g_hm, 0);
        }
    }
    if (lc > g_kmax[k]) {
        g_kmax[k] = lc;
        prof_snap(&g_hk[k], 0);
    }
    if (g_re_focus.set) {
        uint64_t fc = 0;
        for (uint32_t i = 0; i < g_n_h; i++) {
            fc += re_match(&g_re_focus, g_syms[g_h_touched[i]].name) ? g_h[g_h_touched[i]] : 0u;
        }
        if (fc > g_fmax[k]) {
            g_fmax[k] = fc;
            prof_snap(&g_hf[k], 1);
        }
    }
    if (!g_kmin_set[k] || lc < g_kmin[k]) {
        g_kmin_set[k] = 1;
        g_kmin[k] = lc;
        prof_snap(&g_hn[k], 0);
    }
}

/* h and hp cleared (at every kind's mark, as COUNT_AWK's delete h; delete hp). */
static void prof_clear(void)
{
    for (uint32_t i = 0; i < g_n_h; i++) {
        g_h[g_h_touched[i]] = 0;
    }
    g_n_h = 0;
    for (uint32_t i = 0; i < g_n_hp; i++) {
        g_hp_touched[i]->hp = 0;
    }
    g_n_hp = 0;
}

/* snap as "count symbol" lines into PREFIX SUFFIX (no file for a snapshot never taken). */
static void prof_write_snap(const snap_t *snap, const char *suffix, int taken)
{
    char path[4096];
    snprintf(path, sizeof path, "%s%s", g_prof, suffix);
    FILE *f = taken ? fopen(path, "w") : NULL;
    if (f == NULL) {
        return;
    }
    for (uint32_t i = 0; i < snap->n; i++) {
        fprintf(f, "%llu %s\n", (unsigned long long)snap->cnt[i], g_syms[snap->sym[i]].name);
    }
    fclose(f);
}

/* The profile files, at exit. */
static void prof_write(void)
{
    char path[4096];
    FILE *f = g_nexec > 0 ? fopen(g_prof, "w") : NULL;
    for (uint32_t s = 0; f != NULL && s < g_n_syms; s++) {
        if (g_tot[s] > 0) {
            fprintf(f, "%llu %s\n", (unsigned long long)(g_tot[s] / g_nexec), g_syms[s].name);
        }
    }
    if (f != NULL) {
        fclose(f);
    }
    snprintf(path, sizeof path, "%s.pc", g_prof);
    f = g_nexec > 0 ? fopen(path, "w") : NULL;
    for (uint32_t h = 0; f != NULL && h < INSN_HASH; h++) {
        if (g_insns[h].used && g_insns[h].tp > 0) {
            fprintf(f, "%.2f %08llx %s\n", (double)g_insns[h].tp / (double)g_nexec,
                    (unsigned long long)g_insns[h].addr, g_syms[g_insns[h].sym].name);
        }
    }
    if (f != NULL) {
        fclose(f);
    }
    prof_write_snap(&g_hm, ".maxdmp", g_maxdp > 0);
    for (int k = 0; k < N_KINDS; k++) {
        char suffix[32];
        snprintf(suffix, sizeof suffix, ".max.%s", KIND_NAMES[k]);
        prof_write_snap(&g_hk[k], suffix, g_kmax[k] > 0);
        snprintf(suffix, sizeof suffix, ".focus.%s", KIND_NAMES[k]);
        prof_write_snap(&g_hf[k], suffix, g_fmax[k] > 0);
        snprintf(suffix, sizeof suffix, ".min.%s", KIND_NAMES[k]);
        prof_write_snap(&g_hn[k], suffix, g_kmin_set[k]);
    }
}

/* cm_port_mark_begin: a counted tick starts (and the boot, if one runs, ends). */
static void on_begin(acct_t *a)
{
    if (a->inboot) {
        fprintf(g_out, "boot %llu %llu\n", (unsigned long long)a->bc, (unsigned long long)a->ba);
        a->inboot = 0;
    }
    a->inb = 1;
    a->c = a->part = a->dpart = a->act = 0;
    a->inpart = a->dmp = a->indmp = a->inisr = a->cmt = 0;
    g_n_isr = g_n_isr_calls = 0;
}

/* cm_port_mark_end: the tick's counts are kept until its kind's mark; a skill check ends at the
 * first tick that ran none of it. */
static void on_end(acct_t *a)
{
    if (a->inb && g_n_isr > 0) {
        g_isr_lost++; /* the loop's code ends a tick: an interrupt still open was missed */
    }
    if (a->inb) {
        a->done = 1;
        a->lc = a->c;
        a->lp = a->part;
        a->ld = (uint64_t)a->dmp;
        a->ldp = a->dpart;
        a->lcm = (uint64_t)a->cmt;
        a->la = a->act;
    }
    if (a->chk_tick > 0) {
        a->chk_ticks++;
        if (a->chk_tick > a->chk_max) {
            a->chk_max = a->chk_tick;
        }
    }
    if (a->chk_tick == 0 && a->chk_ticks > 0) {
        fprintf(g_out, "check %llu %llu %llu\n", (unsigned long long)a->chk_total,
                (unsigned long long)a->chk_ticks, (unsigned long long)a->chk_max);
        a->chk_total = a->chk_ticks = a->chk_max = 0;
    }
    a->chk_tick = 0;
    a->inb = 0;
}

/* cm_port_mark_KIND: the last tick's line, its soft-float helpers summed into the kind's. */
static void on_kind(acct_t *a, int k)
{
    if (a->done) {
        fprintf(g_out, "%s %llu %llu %llu %llu %llu %llu\n", KIND_NAMES[k],
                (unsigned long long)a->lc, (unsigned long long)a->lp, (unsigned long long)a->ld,
                (unsigned long long)a->ldp, (unsigned long long)a->lcm, (unsigned long long)a->la);
        a->done = 0;
        if (g_prof != NULL) {
            prof_tick(k, a->lc, a->ld, a->ldp);
        }
        for (uint32_t i = 0; i < g_n_sf_touched; i++) {
            const uint32_t s = g_sf_touched[i];
            g_SFI[k][s] += g_sfi[s];
            g_SFC[k][s] += g_sfc[s];
        }
    }
    for (uint32_t i = 0; i < g_n_sf_touched; i++) {
        g_sfi[g_sf_touched[i]] = 0;
        g_sfc[g_sf_touched[i]] = 0;
    }
    g_n_sf_touched = 0;
    if (g_prof != NULL) {
        prof_clear();
    }
}

/* Entered from its caller's code, left when the caller's code runs again. */
static void enter_leave(int *in, int32_t *caller, int enters, int32_t s, int32_t prev)
{
    if (!*in && enters) {
        *in = 1;
        *caller = prev;
    } else if (*in && s == *caller) {
        *in = 0;
    }
}

/* The boot: every instruction from Reset_Handler's first to the first counted tick, and those
 * inside app_init. */
static void boot_insn(acct_t *a, int32_t s, uint32_t f)
{
    if (!a->inboot && (f & F_RESET)) {
        a->inboot = 1;
        a->bc = a->ba = 0;
        a->ininit = 0;
    }
    if (a->inboot) {
        a->bc++;
        enter_leave(&a->ininit, &a->initcaller, (f & F_APPINIT) != 0, s, a->bprev);
        a->ba += a->ininit ? 1u : 0u;
        a->bprev = s;
    }
}


/* The interrupts inside a tick, exactly: one is taken when its *_Handler runs from elsewhere than
 * its own code or a return into it, or right after an exception return (tail-chained); it ends
 * at its exception return (a return with none of its calls open), whatever instruction of the
 * interrupted code comes next. 1 while in one. */
static int isr_track(acct_t *a, const insn_t *cur, uint32_t f)
{
    const insn_t *p = g_prev_insn;
    int resumed = 0, returned = 0;
    if (g_n_isr > 0 && p != NULL && p->xfer == I_CALL) {
        if (g_n_isr_calls < ISR_DEPTH) {
            g_isr_calls[g_n_isr_calls++] = p->addr + p->size;
        } else {
            g_isr_lost++;
        }
    } else if (g_n_isr > 0 && p != NULL && p->xfer == I_RET && cur->addr != p->addr + p->size) {
        if (g_n_isr_calls > g_isr_base[g_n_isr - 1u]) {
            if (cur->addr == g_isr_calls[g_n_isr_calls - 1u]) {
                g_n_isr_calls--;
                resumed = 1;
            }
        } else {
            g_n_isr--; /* the exception return */
            resumed = g_n_isr > 0;
            returned = 1;
        }
    }
    /* a handler entered again right at its exception return: tail-chained, the same interrupt */
    if ((f & F_HANDLER) && !resumed && (p == NULL || p->sym != cur->sym || returned)) {
        if (g_n_isr < ISR_DEPTH) {
            g_isr_base[g_n_isr++] = g_n_isr_calls;
        } else {
            g_isr_lost++;
        }
    }
    a->inisr = g_n_isr > 0;
    return a->inisr;
}

/* An instruction inside a counted tick. */
static void tick_insn(acct_t *a, const insn_t *cur, int32_t s, uint32_t f)
{
    a->c++;
    if ((f & F_ACT) && a->act == 0u) {
        a->act = a->c; /* the instructions from the tick's start to its actuator write */
    }
    if (f & F_SOFTF) {
        if (g_sfi[s] == 0 && g_sfc[s] == 0) {
            g_sf_touched[g_n_sf_touched++] = (uint32_t)s;
        }
        g_sfi[s]++;
        g_sfc[s] += s != a->last ? 1u : 0u;
    }
    a->last = s;
    a->cmt |= (f & F_COMMIT) != 0;
    /* an interrupt taken inside the tick counts in the tick, not in a part it interrupts */
    if (isr_track(a, cur, f)) {
        return; /* prev stays the interrupted code's: a part's caller is never a handler */
    }
    if (f & F_HANDLER) {
        g_isr_lost++; /* a handler's code outside an interrupt: its entry was missed */
    }
    const int was_in = a->inpart;
    enter_leave(&a->inpart, &a->caller, (f & (F_DMP | F_LAW)) != 0, s, a->prev);
    if (!was_in && a->inpart && (f & F_DMP)) {
        a->dmp = 1;
    }
    a->part += a->inpart ? 1u : 0u;
    enter_leave(&a->indmp, &a->dcaller, (f & F_DMP) != 0, s, a->prev);
    a->dpart += a->indmp ? 1u : 0u;
    enter_leave(&a->inchk, &a->chkcaller, (f & F_CHK) != 0, s, a->prev);
    if (a->inchk) {
        a->chk_total++;
        a->chk_tick++;
    }
    a->prev = s;
}

/* The counter check's regions: the instructions between cm_port_mark_begin and _end. */
static void count_insn(acct_t *a, uint32_t f)
{
    if (f & F_BEGIN) {
        a->inb = 1;
        a->c = 0;
    } else if (f & F_END) {
        if (a->inb) {
            fprintf(g_out, "%llu\n", (unsigned long long)a->c);
        }
        a->inb = 0;
    } else if (a->inb) {
        a->c++;
    }
}

static void finish(void);

static void on_insn(unsigned int vcpu, void *udata)
{
    (void)vcpu;
    const int32_t s = ((const insn_t *)udata)->sym;
    if (g_out == NULL) {
        return;
    }
    if (g_log != NULL) {
        fprintf(g_log, "%08llx %s\n", (unsigned long long)((const insn_t *)udata)->addr,
                g_syms[s].name);
    }
    const sym_t *y = &g_syms[s];
    acct_t *a = &g_a;
    if (g_count_mode) {
        count_insn(a, y->flags);
    } else if (y->flags & F_BEGIN) {
        on_begin(a);
    } else if (y->flags & F_END) {
        if (a->inb) {
            (void)isr_track(a, (const insn_t *)udata, y->flags); /* one taken right before it */
        }
        on_end(a);
    } else if (y->kind >= 0) {
        on_kind(a, y->kind);
    } else {
        boot_insn(a, s, y->flags);
        if (a->inb) {
            tick_insn(a, (const insn_t *)udata, s, y->flags);
            if (g_prof != NULL) {
                prof_insn((insn_t *)udata);
            }
        }
    }
    g_prev_insn = (const insn_t *)udata;
    if (g_limit != 0u && ++g_n_executed == g_limit) {
        finish(); /* limit=N: the lines of the first N instructions, then "limit N" */
    }
}

static void on_tb_trans(qemu_plugin_id_t id, struct qemu_plugin_tb *tb)
{
    (void)id;
    const size_t n = qemu_plugin_tb_n_insns(tb);
    for (size_t i = 0; i < n; i++) {
        struct qemu_plugin_insn *insn = qemu_plugin_tb_get_insn(tb, i);
        insn_t *r = insn_at(qemu_plugin_insn_vaddr(insn), insn);
        qemu_plugin_register_vcpu_insn_exec_cb(insn, on_insn, QEMU_PLUGIN_CB_NO_REGS, r);
    }
}

/* The soft-float lines, then the files closed (at qemu's exit or at limit=N). */
static void finish(void)
{
    if (g_out == NULL) {
        return;
    }
    if (!g_count_mode) {
        for (int k = 0; k < N_KINDS; k++) {
            for (uint32_t s = 0; s < g_n_syms; s++) {
                if (g_SFI[k][s] > 0) {
                    fprintf(g_out, "softfloat %s %s %llu %llu\n", KIND_NAMES[k], g_syms[s].name,
                            (unsigned long long)g_SFC[k][s], (unsigned long long)g_SFI[k][s]);
                }
            }
        }
    }
    if (!g_count_mode && g_prof != NULL) {
        prof_write();
    }
    if (g_isr_lost > 0) {
        fprintf(g_out, "isr_lost %llu\n", (unsigned long long)g_isr_lost);
    }
    if (g_limit != 0u && g_n_executed == g_limit) {
        fprintf(g_out, "limit %llu\n", (unsigned long long)g_limit);
    }
    fclose(g_out);
    g_out = NULL;
    if (g_log != NULL) {
        fclose(g_log);
        g_log = NULL;
    }
}

static void on_qemu_exit(qemu_plugin_id_t id, void *udata)
{
    (void)id;
    (void)udata;
    finish();
}

/* Compile ere (if given) into re: 0, else -1 with a message. */
static int re_set(ere_t *re, const char *ere)
{
    if (ere == NULL) {
        return 0;
    }
    if (regcomp(&re->re, ere, REG_EXTENDED | REG_NOSUB) != 0) {
        fprintf(stderr, "tick_plugin: bad regular expression %s\n", ere);
        return -1;
    }
    re->set = 1;
    return 0;
}

QEMU_PLUGIN_EXPORT int qemu_plugin_install(qemu_plugin_id_t id, const qemu_info_t *info, int argc,
                                           char **argv)
{
    const char *out = NULL;
    const char *dmp = NULL, *commit = NULL, *softf = NULL, *chk = NULL, *focus = NULL;
    (void)info;
    for (int i = 0; i < argc; i++) {
        const char *v = strchr(argv[i], '=');
        const size_t kl = v != NULL ? (size_t)(v - argv[i]) : 0u;
        v = v != NULL ? v + 1 : "";
#define KEY(k) (kl == sizeof(k) - 1 && strncmp(argv[i], k, kl) == 0)
        if (KEY("out")) {
            out = v;
        } else if (KEY("mode")) {
            g_count_mode = strcmp(v, "count") == 0;
        } else if (KEY("dmp")) {
            dmp = v;
        } else if (KEY("law")) {
            g_law = v;
        } else if (KEY("commit")) {
            commit = v;
        } else if (KEY("softf")) {
            softf = v;
        } else if (KEY("limit")) {
            g_limit = strtoull(v, NULL, 10);
        } else if (KEY("log")) {
            if ((g_log = fopen(v, "w")) == NULL) {
                fprintf(stderr, "tick_plugin: cannot write %s\n", v);
                return -1;
            }
        } else if (KEY("prof")) {
            g_prof = v;
        } else if (KEY("focus")) {
            focus = v;
        } else if (KEY("chk")) {
            chk = v;
        } else {
            fprintf(stderr, "tick_plugin: unknown argument %s\n", argv[i]);
            return -1;
        }
#undef KEY
    }
    if (out == NULL || (g_out = fopen(out, "w")) == NULL) {
        fprintf(stderr, "tick_plugin: out=FILE missing or not writable\n");
        return -1;
    }
    if (re_set(&g_re_dmp, dmp) || re_set(&g_re_commit, commit) || re_set(&g_re_softf, softf) ||
        re_set(&g_re_chk, chk) || re_set(&g_re_focus, focus)) {
        return -1;
    }
    g_insns = calloc(INSN_HASH, sizeof *g_insns);
    g_hp_touched = g_prof != NULL ? calloc(INSN_HASH, sizeof *g_hp_touched) : NULL;
    if (g_insns == NULL || (g_prof != NULL && g_hp_touched == NULL)) {
        return -1;
    }
    qemu_plugin_register_vcpu_tb_trans_cb(id, on_tb_trans);
    qemu_plugin_register_atexit_cb(id, on_qemu_exit, NULL);
    return 0;
}
