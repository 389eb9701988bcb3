/*
 * A QEMU TCG plugin that counts, for each address that ran, the instructions executed there
 * and how often control went on from there to anywhere but the next instruction (a taken
 * branch, a call, a return), for `obscura firmware`'s profile and cycle estimates. The harness
 * attributes the addresses to the firmware's functions and weighs each instruction by its
 * core's timings.
 *
 * Arguments: `out=PATH`, the file the counts go to; `begin=ADDRESS` and `end=ADDRESS` (hex),
 * optional, the entries of the two functions the firmware calls around each frame: the counts
 * between them are written again per frame. The file holds
 *
 *   insn <address> <bytes> <disassembly>            each address translated, once
 *   run <address> <executed> <taken>                the whole run
 *   frame <n> <address> <executed> <taken>          frame n (from 1), for each address it ran
 *
 * with the numbers in decimal but the addresses, in hex.
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
enum qemu_plugin_cb_flags { QEMU_PLUGIN_CB_NO_REGS, QEMU_PLUGIN_CB_R_REGS, QEMU_PLUGIN_CB_RW_REGS };

typedef void (*qemu_plugin_vcpu_tb_trans_cb_t)(qemu_plugin_id_t id, struct qemu_plugin_tb *tb);
typedef void (*qemu_plugin_udata_cb_t)(qemu_plugin_id_t id, void *userdata);
typedef void (*qemu_plugin_vcpu_udata_cb_t)(unsigned int vcpu_index, void *userdata);

void qemu_plugin_register_vcpu_tb_trans_cb(qemu_plugin_id_t id, qemu_plugin_vcpu_tb_trans_cb_t cb);
void qemu_plugin_register_atexit_cb(qemu_plugin_id_t id, qemu_plugin_udata_cb_t cb, void *userdata);
void qemu_plugin_register_vcpu_tb_exec_cb(struct qemu_plugin_tb *tb, qemu_plugin_vcpu_udata_cb_t cb,
                                          enum qemu_plugin_cb_flags flags, void *userdata);
void qemu_plugin_register_vcpu_insn_exec_cb(struct qemu_plugin_insn *insn,
                                            qemu_plugin_vcpu_udata_cb_t cb,
                                            enum qemu_plugin_cb_flags flags, void *userdata);
size_t qemu_plugin_tb_n_insns(const struct qemu_plugin_tb *tb);
struct qemu_plugin_insn *qemu_plugin_tb_get_insn(const struct qemu_plugin_tb *tb, size_t idx);
uint64_t qemu_plugin_insn_vaddr(const struct qemu_plugin_insn *insn);
size_t qemu_plugin_insn_size(const struct qemu_plugin_insn *insn);
char *qemu_plugin_insn_disas(const struct qemu_plugin_insn *insn);
void qemu_plugin_register_vcpu_insn_exec_inline(struct qemu_plugin_insn *insn, enum qemu_plugin_op op,
                                                void *ptr, uint64_t imm);
void qemu_plugin_outs(const char *string);

__attribute__((visibility("default"))) int qemu_plugin_version = 1;

/*
 * One counter per translated instruction; an address translated twice has two, summed by the
 * harness. `at_begin` holds the counts when the frame under way began.
 */
struct counter {
    uint64_t address;
    uint64_t executed;
    uint64_t taken;
    uint64_t executed_at_begin;
    uint64_t taken_at_begin;
    size_t size;
    char *text;
};

/* Blocks of counters that never move, since QEMU's generated code adds to them in place. */
#define BLOCK 65536
struct block {
    struct counter counters[BLOCK];
    size_t used;
    struct block *next;
};

/* A translated block: where control goes when it falls through, and its last instruction. */
struct translated_block {
    uint64_t start;
    uint64_t fall_through;
    struct counter *last;
};

static struct block *blocks;
static FILE *out;
static uint64_t begin_address = UINT64_MAX, end_address = UINT64_MAX;
static unsigned frames;
/* The block that ran last: its last instruction passed control to the block running now. */
static const struct translated_block *previous;

static void *allocate(size_t size)
{
    void *memory = calloc(1, size);
    if (!memory) {
        qemu_plugin_outs("profile: out of memory\n");
        abort();
    }
    return memory;
}

static struct counter *new_counter(uint64_t address, size_t size, char *text)
{
    if (!blocks || blocks->used == BLOCK) {
        struct block *block = allocate(sizeof *block);
        block->next = blocks;
        blocks = block;
    }
    struct counter *counter = &blocks->counters[blocks->used++];
    counter->address = address;
    counter->size = size;
    counter->text = text;
    return counter;
}

/* Each block run: the one before it went elsewhere than its fall-through, or did not. */
static void block_executed(unsigned int vcpu, void *userdata)
{
    (void)vcpu;
    const struct translated_block *block = userdata;
    if (previous && previous->fall_through != block->start) {
        previous->last->taken++;
    }
    previous = block;
}

static void frame_begins(unsigned int vcpu, void *userdata)
{
    (void)vcpu;
    (void)userdata;
    for (struct block *block = blocks; block; block = block->next) {
        for (size_t i = 0; i < block->used; i++) {
            struct counter *c = &block->counters[i];
            c->executed_at_begin = c->executed;
            c->taken_at_begin = c->taken;
        }
    }
}

static void frame_ends(unsigned int vcpu, void *userdata)
{
    (void)vcpu;
    (void)userdata;
    frames++;
    for (struct block *block = blocks; block; block = block->next) {
        for (size_t i = 0; i < block->used; i++) {
            const struct counter *c = &block->counters[i];
            if (c->executed > c->executed_at_begin) {
                fprintf(out, "frame %u %" PRIx64 " %" PRIu64 " %" PRIu64 "\n", frames, c->address,
                        c->executed - c->executed_at_begin, c->taken - c->taken_at_begin);
            }
        }
    }
}

static void translated(qemu_plugin_id_t id, struct qemu_plugin_tb *tb)
{
    (void)id;
    size_t n = qemu_plugin_tb_n_insns(tb);
    if (n == 0) {
        return;
    }
    struct translated_block *block = allocate(sizeof *block);
    for (size_t i = 0; i < n; i++) {
        struct qemu_plugin_insn *insn = qemu_plugin_tb_get_insn(tb, i);
        uint64_t address = qemu_plugin_insn_vaddr(insn);
        struct counter *counter =
            new_counter(address, qemu_plugin_insn_size(insn), qemu_plugin_insn_disas(insn));
        qemu_plugin_register_vcpu_insn_exec_inline(insn, QEMU_PLUGIN_INLINE_ADD_U64,
                                                   &counter->executed, 1);
        if (address == begin_address) {
            qemu_plugin_register_vcpu_insn_exec_cb(insn, frame_begins, QEMU_PLUGIN_CB_NO_REGS, NULL);
        }
        if (address == end_address) {
            qemu_plugin_register_vcpu_insn_exec_cb(insn, frame_ends, QEMU_PLUGIN_CB_NO_REGS, NULL);
        }
        if (i == 0) {
            block->start = address;
        }
        if (i == n - 1) {
            block->fall_through = address + counter->size;
            block->last = counter;
        }
    }
    qemu_plugin_register_vcpu_tb_exec_cb(tb, block_executed, QEMU_PLUGIN_CB_NO_REGS, block);
}

static void finished(qemu_plugin_id_t id, void *userdata)
{
    (void)id;
    (void)userdata;
    for (struct block *block = blocks; block; block = block->next) {
        for (size_t i = 0; i < block->used; i++) {
            const struct counter *c = &block->counters[i];
            fprintf(out, "insn %" PRIx64 " %zu %s\n", c->address, c->size, c->text ? c->text : "?");
            if (c->executed) {
                fprintf(out, "run %" PRIx64 " %" PRIu64 " %" PRIu64 "\n", c->address, c->executed,
                        c->taken);
            }
        }
    }
    fclose(out);
}

/* Parses the hex address of argument `arg` after its `name=`, if it is that argument. */
static int address_argument(const char *arg, const char *name, uint64_t *address)
{
    size_t length = strlen(name);
    if (strncmp(arg, name, length) != 0 || arg[length] != '=') {
        return 0;
    }
    *address = strtoull(arg + length + 1, NULL, 16);
    return 1;
}

__attribute__((visibility("default"))) int qemu_plugin_install(qemu_plugin_id_t id,
                                                               const qemu_info_t *info,
                                                               int argc, char **argv)
{
    (void)info;
    const char *out_path = NULL;
    for (int i = 0; i < argc; i++) {
        if (strncmp(argv[i], "out=", 4) == 0) {
            out_path = argv[i] + 4;
        } else if (!address_argument(argv[i], "begin", &begin_address) &&
                   !address_argument(argv[i], "end", &end_address)) {
            qemu_plugin_outs("profile: unknown argument\n");
            return -1;
        }
    }
    if (!out_path) {
        qemu_plugin_outs("profile: give the counts' file as out=PATH\n");
        return -1;
    }
    out = fopen(out_path, "w");
    if (!out) {
        qemu_plugin_outs("profile: cannot write the counts\n");
        return -1;
    }
    qemu_plugin_register_vcpu_tb_trans_cb(id, translated);
    qemu_plugin_register_atexit_cb(id, finished, NULL);
    return 0;
}
