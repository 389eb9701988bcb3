//! Cycles, estimated from the instructions a firmware run executed. QEMU models no timing: its
//! plugin (`host/qemu/profile.c`) gives each address's instruction as QEMU disassembles it, how
//! often it ran and how often control went on from it to anywhere but the next instruction;
//! each is weighed here by the documented timings of the core on the target's board ([`Core`]).
//!
//! What no table says is assumed: memory without wait states (code in RAM or a cache that hits,
//! as the manuals' tables assume), and of a documented range the figure [`Core`] names.

use crate::firmware::Target;
use std::collections::BTreeMap;

/// The core whose documented timings price a target's instructions.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Core {
    /// Arm Cortex-M0+ (its Technical Reference Manual, DDI 0484C, table 3.1) with the
    /// single-cycle multiplier, as the RP2040 has it: a load or store 2 cycles, a taken branch
    /// 2, `bl` 3, `push`/`pop` 1 + N registers (3 + N returning).
    CortexM0Plus,
    /// Arm Cortex-M4 (its TRM, 100166, tables 3-1 and 3-2): multiplies 1 cycle, divides 2–12
    /// (taken as 7), a load 2 or 1 after a load or store, a store with an immediate offset 1,
    /// a branch 1 + P where the pipeline refills (P of 1–3, taken as 2), VFP 1, its multiply-adds 3,
    /// `vdiv` and `vsqrt` 14.
    CortexM4,
    /// Arm Cortex-M33, for which Arm publishes no table: priced as the Cortex-M4, the model
    /// LLVM schedules it by.
    CortexM33,
    /// Hazard3 as the RP2350 configures it (Hazard3's `doc/sections/instruction_timings.adoc`;
    /// the fast multiplier and the branch predictor): multiplies 1 cycle, divides 18 (19
    /// signed), a load 1 or 2 when the next instruction uses its result, jumps 2, a branch 1
    /// or 2 when mispredicted (the predictor takes a backward branch, never a forward one).
    Hazard3,
}

impl Core {
    /// The core on `target`'s board.
    pub fn of(target: Target) -> Self {
        match target {
            Target::M4f => Self::CortexM4,
            Target::M0 => Self::CortexM0Plus,
            Target::M33 => Self::CortexM33,
            Target::Rv32 => Self::Hazard3,
        }
    }

    /// Its name, as the tables print it.
    pub fn name(self) -> &'static str {
        match self {
            Self::CortexM0Plus => "Cortex-M0+",
            Self::CortexM4 => "Cortex-M4",
            Self::CortexM33 => "Cortex-M33",
            Self::Hazard3 => "Hazard3",
        }
    }

    /// Whose documented timings price it, as the tables say.
    pub fn timings(self) -> &'static str {
        match self {
            Self::CortexM0Plus => "the Cortex-M0+'s documented timings",
            Self::CortexM4 => "the Cortex-M4's documented timings",
            Self::CortexM33 => {
                "the Cortex-M4's documented timings (Arm publishes none for the Cortex-M33)"
            }
            Self::Hazard3 => "Hazard3's documented timings",
        }
    }

    fn is_risc_v(self) -> bool {
        self == Self::Hazard3
    }
}

/// What an instruction does, for where the cycles go.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Class {
    /// Arithmetic, logic, moves, shifts, bit manipulation.
    Alu,
    /// Integer multiplies.
    Multiply,
    /// Integer divides and remainders.
    Divide,
    /// Loads and stores of one register.
    LoadStore,
    /// Loads and stores of several (`push`, `pop`, `ldm`, `stm`, `ldrd`).
    LoadStoreMultiple,
    /// Branches, calls and returns.
    Branch,
    /// Floating-point instructions but divides and roots.
    Float,
    /// Floating-point divides and square roots.
    FloatDivide,
}

impl Class {
    /// Its name, as the tables print it.
    pub fn name(self) -> &'static str {
        match self {
            Self::Alu => "arithmetic, logic and moves",
            Self::Multiply => "integer multiplies",
            Self::Divide => "integer divides",
            Self::LoadStore => "loads and stores",
            Self::LoadStoreMultiple => "loads and stores of several registers",
            Self::Branch => "branches, calls and returns",
            Self::Float => "floating point",
            Self::FloatDivide => "floating-point divides and roots",
        }
    }
}

/// An instruction as QEMU disassembles it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Instruction {
    /// Its bytes.
    pub size: u64,
    /// The mnemonic in lower case, without Thumb's width or a VFP type (`ldr`, `vmla`, `beq`).
    mnemonic: String,
    /// The operands as written, without RISC-V's comment.
    operands: String,
    /// Where a RISC-V branch or jump goes (its comment).
    target: Option<u64>,
}

impl Instruction {
    /// `text` as QEMU's disassembler writes it for `core`: on Arm `mnemonic operands`, on
    /// RISC-V the encoding first and a branch's destination in a comment (`0072f463  bleu
    /// t2,t0,8  # 0x8000009c`).
    pub fn parse(text: &str, size: u64, core: Core) -> Self {
        let text = text.trim();
        let text = if core.is_risc_v() {
            text.split_once(char::is_whitespace)
                .map_or("", |(_, rest)| rest)
        } else {
            text
        };
        let (text, comment) = text
            .split_once('#')
            .filter(|_| core.is_risc_v())
            .map_or((text, None), |(text, comment)| (text, Some(comment)));
        let (mnemonic, operands) = text
            .trim()
            .split_once(char::is_whitespace)
            .unwrap_or((text, ""));
        let mnemonic = mnemonic
            .split('.')
            .next()
            .unwrap_or("")
            .to_ascii_lowercase();
        let target = comment
            .and_then(|c| c.trim().strip_prefix("0x"))
            .and_then(|hex| u64::from_str_radix(hex, 16).ok());
        Self {
            size,
            mnemonic,
            operands: operands.trim().to_owned(),
            target,
        }
    }

    /// The operands, split at commas outside brackets and braces.
    fn operand_list(&self) -> Vec<&str> {
        let mut list = Vec::new();
        let (mut depth, mut start) = (0_i32, 0);
        for (i, c) in self.operands.char_indices() {
            match c {
                '[' | '{' | '(' => depth += 1,
                ']' | '}' | ')' => depth -= 1,
                ',' if depth == 0 => {
                    list.push(self.operands[start..i].trim());
                    start = i + 1;
                }
                _ => {}
            }
        }
        let last = self.operands[start..].trim();
        if !last.is_empty() {
            list.push(last);
        }
        list
    }
}

/// How often an instruction ran, and how often control went on from it elsewhere than to
/// the next instruction.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Count {
    /// Times executed.
    pub executed: u64,
    /// Times it passed control elsewhere (a taken branch, a call, a return, an exception).
    pub taken: u64,
}

/// Instructions and their cycles, in all and by [`Class`].
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Estimate {
    /// Instructions executed.
    pub instructions: u64,
    /// Cycles they take.
    pub cycles: u64,
    /// Per class, in [`Class`]'s order: instructions and cycles (the classes that ran).
    pub by_class: Vec<(Class, u64, u64)>,
    /// Per mnemonic, the most cycles first: instructions and cycles.
    pub by_mnemonic: Vec<(String, u64, u64)>,
}

/// The cycles of the instructions `counted` on `core`, each address's instruction in
/// `instructions` (one without its instruction counts as one cycle of arithmetic).
pub fn estimate(
    core: Core,
    instructions: &BTreeMap<u64, Instruction>,
    counted: &BTreeMap<u64, Count>,
) -> Estimate {
    let mut by_class: BTreeMap<Class, (u64, u64)> = BTreeMap::new();
    let mut by_mnemonic: BTreeMap<&str, (u64, u64)> = BTreeMap::new();
    for (&address, &count) in counted {
        let mnemonic = instructions
            .get(&address)
            .map_or("?", |i| i.mnemonic.as_str());
        let (class, cycles) = match instructions.get(&address) {
            Some(instruction) => {
                let next = instructions.get(&(address + instruction.size));
                let previous = instructions
                    .range(..address)
                    .next_back()
                    .map(|(&at, i)| (at, i))
                    .filter(|(at, i)| at + i.size == address)
                    .map(|(_, i)| i);
                let neighbours = Neighbours { previous, next };
                cost(core, address, instruction, neighbours, count)
            }
            None => (Class::Alu, count.executed),
        };
        for entry in [
            by_class.entry(class).or_default(),
            by_mnemonic.entry(mnemonic).or_default(),
        ] {
            entry.0 += count.executed;
            entry.1 += cycles;
        }
    }
    let mut by_mnemonic: Vec<(String, u64, u64)> = by_mnemonic
        .into_iter()
        .map(|(m, (n, cycles))| (m.to_owned(), n, cycles))
        .collect();
    by_mnemonic.sort_by(|a, b| b.2.cmp(&a.2).then_with(|| a.0.cmp(&b.0)));
    Estimate {
        instructions: by_class.values().map(|(n, _)| n).sum(),
        cycles: by_class.values().map(|(_, c)| c).sum(),
        by_class: by_class
            .into_iter()
            .map(|(class, (n, cycles))| (class, n, cycles))
            .collect(),
        by_mnemonic,
    }
}

/// The instructions before and after one in the code, where they are known.
#[derive(Clone, Copy, Debug)]
struct Neighbours<'a> {
    previous: Option<&'a Instruction>,
    next: Option<&'a Instruction>,
}

/// The class of `instruction` at `address`, and the cycles of its `count` on `core`.
fn cost(
    core: Core,
    address: u64,
    instruction: &Instruction,
    neighbours: Neighbours<'_>,
    count: Count,
) -> (Class, u64) {
    match core {
        Core::CortexM0Plus => cortex_m0_plus(instruction, count),
        Core::CortexM4 | Core::CortexM33 => cortex_m4(instruction, neighbours.previous, count),
        Core::Hazard3 => hazard3(address, instruction, neighbours.next, count),
    }
}

/// Arm's condition codes, which a conditional branch's mnemonic ends in.
const CONDITIONS: [&str; 16] = [
    "eq", "ne", "cs", "hs", "cc", "lo", "mi", "pl", "vs", "vc", "hi", "ls", "ge", "lt", "gt", "le",
];

/// Whether an Arm mnemonic is a branch (`b`, `bl`, `bx`, `blx`, `cbz`, `cbnz`, `b<cond>`).
fn is_arm_branch(mnemonic: &str) -> bool {
    matches!(mnemonic, "b" | "bl" | "bx" | "blx" | "cbz" | "cbnz")
        || mnemonic
            .strip_prefix('b')
            .is_some_and(|cond| CONDITIONS.contains(&cond))
}

/// The registers of an Arm register list (`{r4, r5, lr}`, a VFP `{d8, d9}` as four words).
fn arm_list_words(instruction: &Instruction) -> u64 {
    let Some(list) = instruction
        .operand_list()
        .into_iter()
        .find(|o| o.starts_with('{'))
    else {
        return 1;
    };
    list.trim_matches(|c| c == '{' || c == '}')
        .split(',')
        .map(|r| if r.trim().starts_with('d') { 2 } else { 1 })
        .sum()
}

/// Whether an Arm instruction writes the program counter (a return by `pop` or `ldm`, a
/// `mov pc`, an `ldr pc`).
fn arm_writes_pc(instruction: &Instruction) -> bool {
    let operands = instruction.operand_list();
    operands.first() == Some(&"pc")
        || operands
            .iter()
            .any(|o| o.starts_with('{') && o.contains("pc"))
}

/// Whether an Arm mnemonic loads or stores several registers.
fn is_arm_multiple(mnemonic: &str) -> bool {
    ["push", "pop", "ldm", "stm", "vpush", "vpop", "vldm", "vstm"]
        .iter()
        .any(|m| mnemonic.starts_with(m))
}

/// Whether an Arm mnemonic multiplies integers.
fn is_arm_multiply(mnemonic: &str) -> bool {
    !mnemonic.starts_with('v')
        && (mnemonic.contains("mul")
            || ["mla", "mls", "sml", "smu", "uml", "umaal"]
                .iter()
                .any(|m| mnemonic.starts_with(m)))
}

/// Cortex-M0+ timings.
fn cortex_m0_plus(instruction: &Instruction, count: Count) -> (Class, u64) {
    let Count { executed, taken } = count;
    let m = instruction.mnemonic.as_str();
    if is_arm_branch(m) {
        // A branch is 1 cycle, 2 taken; `bl` (always taken) 3.
        let refill = if m == "bl" { 2 } else { 1 };
        (Class::Branch, executed + refill * taken)
    } else if is_arm_multiple(m) {
        // 1 + N, and a return by `pop` 2 more.
        let refill = if arm_writes_pc(instruction) { 2 } else { 0 };
        let cycles = (1 + arm_list_words(instruction)) * executed + refill * taken;
        (Class::LoadStoreMultiple, cycles)
    } else if m.starts_with("ldr") || m.starts_with("str") {
        (Class::LoadStore, 2 * executed)
    } else if is_arm_multiply(m) {
        (Class::Multiply, executed)
    } else if arm_writes_pc(instruction) {
        (Class::Branch, executed + taken)
    } else {
        (Class::Alu, executed)
    }
}

/// The Cortex-M4's pipeline refill after a taken branch: 1 to 3 cycles, taken as 2.
const M4_REFILL: u64 = 2;

/// Whether an Arm mnemonic loads or stores one register (not `ldrd`/`strd`, not exclusive).
fn is_arm_single(mnemonic: &str) -> bool {
    (mnemonic.starts_with("ldr") || mnemonic.starts_with("str"))
        && !mnemonic.ends_with('d')
        && !mnemonic.contains("ex")
}

/// Cortex-M4 timings (the Cortex-M33's too).
fn cortex_m4(
    instruction: &Instruction,
    previous: Option<&Instruction>,
    count: Count,
) -> (Class, u64) {
    let Count { executed, taken } = count;
    let m = instruction.mnemonic.as_str();
    let refill = if arm_writes_pc(instruction) {
        M4_REFILL * taken
    } else {
        0
    };
    if is_arm_branch(m) {
        (Class::Branch, executed + M4_REFILL * taken)
    } else if is_arm_multiple(m) {
        let class = if m.starts_with('v') {
            Class::Float
        } else {
            Class::LoadStoreMultiple
        };
        (class, (1 + arm_list_words(instruction)) * executed + refill)
    } else if m == "ldrd" || m == "strd" {
        (Class::LoadStoreMultiple, 3 * executed)
    } else if is_arm_single(m) {
        // "Neighboring load and store single instructions can pipeline": a load after one is
        // 1 cycle; "STR Rx,[Ry,#imm] is always one cycle".
        let pipelined = previous.is_some_and(|p| is_arm_single(&p.mnemonic));
        let immediate_store = m.starts_with("str") && !has_register_offset(instruction);
        let cycles = if pipelined || immediate_store { 1 } else { 2 };
        (Class::LoadStore, cycles * executed + refill)
    } else if m == "sdiv" || m == "udiv" {
        (Class::Divide, 7 * executed)
    } else if is_arm_multiply(m) {
        (Class::Multiply, executed)
    } else if m == "vdiv" || m == "vsqrt" {
        (Class::FloatDivide, 14 * executed)
    } else if m.starts_with('v') {
        let cycles = match m {
            "vmla" | "vmls" | "vnmla" | "vnmls" | "vfma" | "vfms" | "vfnma" | "vfnms" => 3,
            "vldr" | "vstr" => 2,
            _ => 1,
        };
        (Class::Float, cycles * executed)
    } else if refill > 0 {
        (Class::Branch, executed + refill)
    } else {
        (Class::Alu, executed)
    }
}

/// Whether an Arm load or store addresses by a register offset (`[r0, r1]`, `[r0, r1, lsl #2]`).
fn has_register_offset(instruction: &Instruction) -> bool {
    instruction
        .operand_list()
        .into_iter()
        .find(|o| o.starts_with('['))
        .and_then(|o| o.trim_matches(|c| c == '[' || c == ']').split(',').nth(1))
        .is_some_and(|offset| !offset.trim().starts_with('#'))
}

/// RISC-V's branches, as QEMU spells them (with their pseudo-instructions).
const RISC_V_BRANCHES: [&str; 16] = [
    "beq", "bne", "blt", "bge", "bltu", "bgeu", "beqz", "bnez", "blez", "bgez", "bltz", "bgtz",
    "bgt", "ble", "bgtu", "bleu",
];

/// RISC-V's jumps, as QEMU spells them.
const RISC_V_JUMPS: [&str; 7] = ["j", "jal", "jr", "jalr", "ret", "call", "tail"];

/// Hazard3 timings, for `instruction` at `address`.
fn hazard3(
    address: u64,
    instruction: &Instruction,
    next: Option<&Instruction>,
    count: Count,
) -> (Class, u64) {
    let Count { executed, taken } = count;
    let m = instruction.mnemonic.as_str();
    if RISC_V_BRANCHES.contains(&m) {
        // The predictor takes a backward branch and passes a forward one; a wrong guess costs
        // a cycle.
        let backward = instruction.target.is_some_and(|t| t < address);
        let mispredicted = if backward {
            executed - taken.min(executed)
        } else {
            taken
        };
        (Class::Branch, executed + mispredicted)
    } else if RISC_V_JUMPS.contains(&m) {
        (Class::Branch, 2 * executed)
    } else if matches!(m, "lb" | "lbu" | "lh" | "lhu" | "lw") {
        let loaded = instruction.operand_list().first().copied().unwrap_or("");
        let stalls = next.is_some_and(|n| risc_v_reads(n, loaded));
        (Class::LoadStore, if stalls { 2 } else { 1 } * executed)
    } else if matches!(m, "sb" | "sh" | "sw") {
        (Class::LoadStore, executed)
    } else if matches!(m, "div" | "rem") {
        (Class::Divide, 19 * executed)
    } else if matches!(m, "divu" | "remu") {
        (Class::Divide, 18 * executed)
    } else if m.starts_with("mul") {
        (Class::Multiply, executed)
    } else {
        (Class::Alu, executed)
    }
}

/// Whether a RISC-V instruction reads `register` early enough to wait for a load: any source
/// but a store's data (which Hazard3 forwards without a stall).
fn risc_v_reads(instruction: &Instruction, register: &str) -> bool {
    if register.is_empty() {
        return false;
    }
    let m = instruction.mnemonic.as_str();
    if m == "ret" {
        return register == "ra";
    }
    let operands = instruction.operand_list();
    let base = |o: &str| {
        o.split_once('(')
            .map(|(_, base)| base.trim_end_matches(')').to_owned())
    };
    let sources: Vec<String> = if matches!(m, "sb" | "sh" | "sw") {
        operands.iter().filter_map(|o| base(o)).collect()
    } else {
        let from = usize::from(!(RISC_V_BRANCHES.contains(&m) || m == "jr"));
        operands
            .iter()
            .skip(from)
            .map(|o| base(o).unwrap_or_else(|| (*o).to_owned()))
            .collect()
    };
    sources.iter().any(|s| s == register)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The instructions of `(address, size, text)`, disassembled for `core`.
    fn code(core: Core, lines: &[(u64, u64, &str)]) -> BTreeMap<u64, Instruction> {
        lines
            .iter()
            .map(|&(at, size, text)| (at, Instruction::parse(text, size, core)))
            .collect()
    }

    fn counts(lines: &[(u64, u64, u64)]) -> BTreeMap<u64, Count> {
        lines
            .iter()
            .map(|&(at, executed, taken)| (at, Count { executed, taken }))
            .collect()
    }

    #[test]
    fn risc_v_text_parses_past_its_encoding_to_a_branch_destination() {
        let i = Instruction::parse(
            "0072f463          bleu                    t2,t0,8                 # 0x8000009c",
            4,
            Core::Hazard3,
        );
        assert_eq!(i.mnemonic, "bleu");
        assert_eq!(i.operand_list(), ["t2", "t0", "8"]);
        assert_eq!(i.target, Some(0x8000_009c));
        let i = Instruction::parse("vmla.f32 s0, s1, s2", 4, Core::CortexM4);
        assert_eq!((i.mnemonic.as_str(), i.target), ("vmla", None));
    }

    #[test]
    fn hazard3_stalls_a_load_whose_result_is_used_next_but_not_a_store_of_it() {
        let core = Core::Hazard3;
        let used = code(
            core,
            &[
                (0, 4, "0 lw a0,12(sp)"),
                (4, 4, "0 add a1,a0,a2"),
                (8, 4, "0 sw a1,0(sp)"),
            ],
        );
        let stored = code(core, &[(0, 4, "0 lw a0,12(sp)"), (4, 4, "0 sw a0,0(a1)")]);
        let addressed = code(core, &[(0, 4, "0 lw a0,12(sp)"), (4, 4, "0 sw a1,0(a0)")]);
        let once = counts(&[(0, 1, 0), (4, 1, 0)]);
        assert_eq!(estimate(core, &used, &once).cycles, 3);
        assert_eq!(estimate(core, &stored, &once).cycles, 2);
        assert_eq!(estimate(core, &addressed, &once).cycles, 3);
    }

    #[test]
    fn hazard3_predicts_a_loop_taken_and_a_forward_branch_not() {
        let core = Core::Hazard3;
        let loop_back = code(core, &[(0x100, 4, "0 bnez a0,-16  # 0xf0")]);
        let forward = code(core, &[(0x100, 4, "0 bnez a0,16  # 0x110")]);
        // Ten runs, nine taken: one misprediction back, nine forward.
        let ran = counts(&[(0x100, 10, 9)]);
        assert_eq!(estimate(core, &loop_back, &ran).cycles, 11);
        assert_eq!(estimate(core, &forward, &ran).cycles, 19);
        let divide = code(core, &[(0, 4, "0 divu a0,a0,a1"), (4, 4, "0 jal ra,8")]);
        assert_eq!(
            estimate(core, &divide, &counts(&[(0, 1, 0), (4, 1, 1)])).cycles,
            20
        );
    }

    #[test]
    fn cortex_m0_plus_prices_branches_calls_and_returns_by_its_table() {
        let core = Core::CortexM0Plus;
        let lines = code(
            core,
            &[
                (0, 2, "beq #0x10"),
                (2, 4, "bl #0x100"),
                (6, 2, "pop {r4, r5, pc}"),
                (8, 2, "ldr r0, [r1, #4]"),
                (10, 2, "muls r0, r1, r0"),
                (12, 2, "bls #0x40"),
                (14, 2, "bics r0, r1"),
            ],
        );
        // beq taken once of twice: 2 + 1; bl 3; pop {3 registers} returning 3 + 3; ldr 2;
        // muls 1; bls (a branch, not `bl`) not taken 1; bics 1.
        let ran = counts(&[
            (0, 2, 1),
            (2, 1, 1),
            (6, 1, 1),
            (8, 1, 0),
            (10, 1, 0),
            (12, 1, 0),
            (14, 1, 0),
        ]);
        let e = estimate(core, &lines, &ran);
        assert_eq!(e.cycles, 3 + 3 + 6 + 2 + 1 + 1 + 1);
        assert_eq!(e.instructions, 8);
    }

    #[test]
    fn cortex_m4_pipelines_neighbouring_loads_and_prices_the_fpu() {
        let core = Core::CortexM4;
        let lines = code(
            core,
            &[
                (0, 2, "ldr r0, [r1, #4]"),
                (2, 2, "ldr r2, [r1, #8]"),
                (4, 2, "str r2, [r1, r3]"),
                (6, 4, "vsqrt.f32 s0, s0"),
                (10, 4, "vfma.f32 s0, s1, s2"),
                (14, 4, "smull r0, r1, r2, r3"),
                (18, 2, "bx lr"),
            ],
        );
        let once = counts(&[
            (0, 1, 0),
            (2, 1, 0),
            (4, 1, 0),
            (6, 1, 0),
            (10, 1, 0),
            (14, 1, 0),
            (18, 1, 1),
        ]);
        // 2 + 1 (pipelined) + 1 (pipelined; a register offset alone is 2) + 14 + 3 + 1 + 1 + 2.
        assert_eq!(estimate(core, &lines, &once).cycles, 25);
    }
}
