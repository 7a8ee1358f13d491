/* Scenario <-> flat parameter block (see sim_params.h). One table names every field, so both
 * sides (host and image) read and write the same order. */
#include "sim_params.h"

#include <stddef.h>
#include <string.h>

typedef enum {
    P_DOUBLE,
    P_INT,
    P_U64,
    P_UNSIGNED,
    P_PLANT,
    P_MODE,
    P_TASK
} ptype_t;

typedef struct {
    size_t offset;
    ptype_t type;
} pfield_t;

#define F(field, type)                        \
    {                                         \
        offsetof(sim_scenario_t, field), type \
    }

static const pfield_t FIELDS[] = {
    F(mode, P_MODE),
    F(plant, P_PLANT),
    F(duration_s, P_DOUBLE),
    F(tail_s, P_DOUBLE),
    F(dt_s, P_DOUBLE),
    F(substeps, P_INT),
    F(seed, P_U64),
    F(start_x_m, P_DOUBLE),
    F(start_y_m, P_DOUBLE),
    F(m_d_kg, P_DOUBLE),
    F(force_max_N, P_DOUBLE),
    F(object.skin_m, P_DOUBLE),
    F(object.surface_m, P_DOUBLE),
    F(object.k1_Npm, P_DOUBLE),
    F(object.k2_Npm, P_DOUBLE),
    F(object.layer_depth_m, P_DOUBLE),
    F(object.d_v_Nspm, P_DOUBLE),
    F(object.m_v_kg, P_DOUBLE),
    F(carriage.carriage_kg, P_DOUBLE),
    F(carriage.act_max_N, P_DOUBLE),
    F(carriage.act_lag_s, P_DOUBLE),
    F(carriage.viscous_Nspm, P_DOUBLE),
    F(carriage.coulomb_N, P_DOUBLE),
    F(op.task, P_TASK),
    F(op.low_N, P_DOUBLE),
    F(op.high_N, P_DOUBLE),
    F(op.level_min_N, P_DOUBLE),
    F(op.level_max_N, P_DOUBLE),
    F(op.jitter, P_DOUBLE),
    F(op.ramp_s, P_DOUBLE),
    F(op.release_s, P_DOUBLE),
    F(op.reaction_min_s, P_DOUBLE),
    F(op.reaction_max_s, P_DOUBLE),
    F(op.dwell_min_s, P_DOUBLE),
    F(op.dwell_max_s, P_DOUBLE),
    F(op.transition_s, P_DOUBLE),
    F(op.layer_timeout_s, P_DOUBLE),
    F(op.hand_damping_Nspm, P_DOUBLE),
    F(op.tremor_frac, P_DOUBLE),
    F(op.duration_s, P_DOUBLE),
    F(tip.noise_N, P_DOUBLE),
    F(tip.bias_N, P_DOUBLE),
    F(tip.range_N, P_DOUBLE),
    F(tip.bits, P_UNSIGNED),
    F(handle.noise_N, P_DOUBLE),
    F(handle.bias_N, P_DOUBLE),
    F(handle.range_N, P_DOUBLE),
    F(handle.bits, P_UNSIGNED),
    F(encoder_m, P_DOUBLE),
    F(delay_samples, P_INT),
    F(vel_cutoff_Hz, P_DOUBLE),
    F(goal_scale, P_DOUBLE),
    F(time_scale, P_DOUBLE),
    F(use_model, P_INT),
    F(end_policy, P_INT),
    F(phase_stop_gain_per_N2, P_DOUBLE),
    F(surface_error_m, P_DOUBLE),
    F(surface_from_contact, P_INT),
};

#define N_FIELDS (sizeof FIELDS / sizeof FIELDS[0])

static double get_field(const sim_scenario_t *sc, const pfield_t *f)
{
    const char *p = (const char *)sc + f->offset;
    switch (f->type) {
    case P_INT: return (double)*(const int *)(const void *)p;
    case P_U64: return (double)*(const uint64_t *)(const void *)p;
    case P_UNSIGNED: return (double)*(const unsigned *)(const void *)p;
    case P_PLANT: return (double)*(const sim_plant_kind_t *)(const void *)p;
    case P_MODE: return (double)*(const sim_mode_t *)(const void *)p;
    case P_TASK: return (double)*(const sim_task_t *)(const void *)p;
    case P_DOUBLE:
    default: return *(const double *)(const void *)p;
    }
}

static void set_field(sim_scenario_t *sc, const pfield_t *f, double v)
{
    char *p = (char *)sc + f->offset;
    switch (f->type) {
    case P_INT: *(int *)(void *)p = (int)v; break;
    case P_U64: *(uint64_t *)(void *)p = (uint64_t)v; break;
    case P_UNSIGNED: *(unsigned *)(void *)p = (unsigned)v; break;
    case P_PLANT: *(sim_plant_kind_t *)(void *)p = (sim_plant_kind_t)(int)v; break;
    case P_MODE: *(sim_mode_t *)(void *)p = (sim_mode_t)(int)v; break;
    case P_TASK: *(sim_task_t *)(void *)p = (sim_task_t)(int)v; break;
    case P_DOUBLE:
    default: *(double *)(void *)p = v; break;
    }
}

static void put_u32(uint8_t *o, uint32_t v)
{
    for (unsigned i = 0; i < 4u; i++) {
        o[i] = (uint8_t)(v >> (8u * i));
    }
}

static uint32_t get_u32(const uint8_t *in)
{
    return (uint32_t)in[0] | ((uint32_t)in[1] << 8) | ((uint32_t)in[2] << 16) |
           ((uint32_t)in[3] << 24);
}

uint32_t sim_params_pack(const sim_scenario_t *sc, const sim_params_dev_t *dev, uint8_t *out,
                         uint32_t cap)
{
    const uint32_t len = SIM_PARAMS_HEADER + 8u * (uint32_t)N_FIELDS;
    if (cap < len) {
        return 0u;
    }
    put_u32(&out[0], SIM_PARAMS_MAGIC);
    put_u32(&out[4], SIM_PARAMS_VERSION);
    put_u32(&out[8], (uint32_t)N_FIELDS);
    put_u32(&out[12], dev->node);
    put_u32(&out[16], dev->host_timeout_ms);
    put_u32(&out[20], dev->flags);
    memcpy(&out[24], dev->seed, SIM_PARAMS_SEED_LEN);
    for (size_t i = 0; i < N_FIELDS; i++) {
        const double v = get_field(sc, &FIELDS[i]);
        uint64_t bits;
        memcpy(&bits, &v, sizeof bits);
        put_u32(&out[SIM_PARAMS_HEADER + 8u * i], (uint32_t)bits);
        put_u32(&out[SIM_PARAMS_HEADER + 8u * i + 4u], (uint32_t)(bits >> 32));
    }
    return len;
}

int sim_params_unpack(const uint8_t *in, uint32_t len, sim_scenario_t *sc, sim_params_dev_t *dev)
{
    if (len < SIM_PARAMS_HEADER || get_u32(&in[0]) != SIM_PARAMS_MAGIC ||
        get_u32(&in[4]) != SIM_PARAMS_VERSION || get_u32(&in[8]) != (uint32_t)N_FIELDS ||
        len < SIM_PARAMS_HEADER + 8u * (uint32_t)N_FIELDS) {
        return -1;
    }
    memset(sc, 0, sizeof(*sc)); /* every field the plant reads follows; no fault */
    dev->node = get_u32(&in[12]);
    dev->host_timeout_ms = get_u32(&in[16]);
    dev->flags = get_u32(&in[20]);
    memcpy(dev->seed, &in[24], SIM_PARAMS_SEED_LEN);
    for (size_t i = 0; i < N_FIELDS; i++) {
        const uint64_t bits = (uint64_t)get_u32(&in[SIM_PARAMS_HEADER + 8u * i]) |
                              ((uint64_t)get_u32(&in[SIM_PARAMS_HEADER + 8u * i + 4u]) << 32);
        double v;
        memcpy(&v, &bits, sizeof v);
        set_field(sc, &FIELDS[i], v);
    }
    return 0;
}
