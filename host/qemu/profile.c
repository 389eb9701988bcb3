/*
 * A QEMU TCG plugin that counts the instructions executed at each address, for
 * `obscura firmware --profile`. At exit it writes one line per address that ran,
 * "<address in hex> <times executed>", to the file named by its argument `out=PATH`;
 * the harness attributes the addresses to the firmware's functions.
 *
 * QEMU 7.2's plugin API, version 1. Debian ships no qemu-plugin.h, so the handful of
 * functions used are declared here as that header declares them.
 *
 * Build: cc -shared -fPIC -O2 -o profile.so profile.c
 */
#include <inttypes.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef uint64_t qemu_plugin_id_t;
typedef struct qemu_info_t qemu_info_t;
struct qemu_plugin_tb;
struct qemu_plugin_insn;
enum qemu_plugin_op { QEMU_PLUGIN_INLINE_ADD_U64 };

typedef void (*qemu_plugin_vcpu_tb_trans_cb_t)(qemu_plugin_id_t id, struct qemu_plugin_tb *tb);
typedef void (*qemu_plugin_udata_cb_t)(qemu_plugin_id_t id, void *userdata);

void qemu_plugin_register_vcpu_tb_trans_cb(qemu_plugin_id_t id, qemu_plugin_vcpu_tb_trans_cb_t cb);
void qemu_plugin_register_atexit_cb(qemu_plugin_id_t id, qemu_plugin_udata_cb_t cb, void *userdata);
size_t qemu_plugin_tb_n_insns(const struct qemu_plugin_tb *tb);
struct qemu_plugin_insn *qemu_plugin_tb_get_insn(const struct qemu_plugin_tb *tb, size_t idx);
uint64_t qemu_plugin_insn_vaddr(const struct qemu_plugin_insn *insn);
void qemu_plugin_register_vcpu_insn_exec_inline(struct qemu_plugin_insn *insn, enum qemu_plugin_op op,
                                                void *ptr, uint64_t imm);
void qemu_plugin_outs(const char *string);

__attribute__((visibility("default"))) int qemu_plugin_version = 1;

/* One counter per translated instruction; an address translated twice has two, summed at exit. */
struct counter {
    uint64_t address;
    uint64_t executed;
};

/* Blocks of counters that never move, since QEMU's generated code adds to them in place. */
#define BLOCK 65536
struct block {
    struct counter counters[BLOCK];
    size_t used;
    struct block *next;
};

static struct block *blocks;
static char *out_path;

static struct counter *new_counter(uint64_t address)
{
    if (!blocks || blocks->used == BLOCK) {
        struct block *block = calloc(1, sizeof *block);
        if (!block) {
            qemu_plugin_outs("profile: out of memory\n");
            abort();
        }
        block->next = blocks;
        blocks = block;
    }
    struct counter *counter = &blocks->counters[blocks->used++];
    counter->address = address;
    return counter;
}

static void translated(qemu_plugin_id_t id, struct qemu_plugin_tb *tb)
{
    (void)id;
    size_t n = qemu_plugin_tb_n_insns(tb);
    for (size_t i = 0; i < n; i++) {
        struct qemu_plugin_insn *insn = qemu_plugin_tb_get_insn(tb, i);
        struct counter *counter = new_counter(qemu_plugin_insn_vaddr(insn));
        qemu_plugin_register_vcpu_insn_exec_inline(insn, QEMU_PLUGIN_INLINE_ADD_U64,
                                                   &counter->executed, 1);
    }
}

static void finished(qemu_plugin_id_t id, void *userdata)
{
    (void)id;
    (void)userdata;
    FILE *out = fopen(out_path, "w");
    if (!out) {
        qemu_plugin_outs("profile: cannot write the counts\n");
        return;
    }
    for (struct block *block = blocks; block; block = block->next) {
        for (size_t i = 0; i < block->used; i++) {
            const struct counter *c = &block->counters[i];
            if (c->executed) {
                fprintf(out, "%" PRIx64 " %" PRIu64 "\n", c->address, c->executed);
            }
        }
    }
    fclose(out);
}

__attribute__((visibility("default"))) int qemu_plugin_install(qemu_plugin_id_t id,
                                                               const qemu_info_t *info,
                                                               int argc, char **argv)
{
    (void)info;
    for (int i = 0; i < argc; i++) {
        if (strncmp(argv[i], "out=", 4) == 0) {
            out_path = strdup(argv[i] + 4);
        }
    }
    if (!out_path) {
        qemu_plugin_outs("profile: give the counts' file as out=PATH\n");
        return -1;
    }
    qemu_plugin_register_vcpu_tb_trans_cb(id, translated);
    qemu_plugin_register_atexit_cb(id, finished, NULL);
    return 0;
}
