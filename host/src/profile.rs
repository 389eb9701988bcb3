//! What a firmware run executed, and where its instructions go (`obscura firmware --profile`).
//! QEMU counts the instructions executed at each address, in the run and in each frame, with a
//! small TCG plugin (`host/qemu/profile.c`, built here by the system's C compiler; [`Counts`]),
//! from which [`crate::cycles`] estimates the frames' cycles. Each address is attributed twice: to the function of the
//! ELF image that holds it (what is out of line: the calls a frame makes), and to a phase of the
//! tracer by the functions inlined there (the image's debug information: release builds keep
//! line tables and inlining), as a sampling profiler with inline frames would.

use crate::cycles::{Core, Count, Instruction};
use crate::firmware::workspace;
use addr2line::Loader;
use anyhow::{Context, Result, anyhow, bail};
use object::{Object, ObjectSymbol, SymbolKind};
use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};
use std::process::Command;

/// A phase of a frame's profile, and the functions outside the core that mark it (the
/// compiler's library, the firmware's own): a function of the core marks the phase its module
/// declares ([`obscura::phase`]; [`core_phase`]). An address belongs to the phase of the
/// innermost function inlined there that marks one (the first phase listed wins). Arithmetic
/// marks [`ARITHMETIC`] only where nothing encloses it that marks another phase: inlined, it is
/// the work of its caller's phase.
struct Phase {
    name: &'static str,
    marks: &'static [&'static str],
}

/// The phases, in the order the table lists them.
const PHASES: [Phase; 10] = [
    Phase {
        name: CAMERA,
        marks: &[],
    },
    Phase {
        name: TESTS,
        marks: &[],
    },
    Phase {
        name: SHADOW_RAYS,
        marks: &[],
    },
    Phase {
        name: SECONDARY_RAYS,
        marks: &[],
    },
    Phase {
        name: SHADING,
        marks: &[],
    },
    Phase {
        name: ARITHMETIC,
        marks: &[],
    },
    Phase {
        name: "compiler library (soft float, 64-bit division, copies)",
        marks: &[
            "compiler_builtins",
            "__aeabi",
            "memcpy",
            "memset",
            "memmove",
        ],
    },
    Phase {
        name: OUTPUT,
        marks: &[
            "obscura_firmware::",
            "obscura_qemu::",
            "embedded_graphics",
            "cortex_m_semihosting::",
        ],
    },
    Phase {
        name: WORDS,
        marks: &[],
    },
    Phase {
        name: BUILD,
        marks: &[],
    },
];

const CAMERA: &str = "primary rays (camera)";
const TESTS: &str = "intersection tests";
const SHADOW_RAYS: &str = "shadow rays (but their intersection tests)";
const SECONDARY_RAYS: &str = "secondary rays: reflection and refraction";
const SHADING: &str = "shading";
const OUTPUT: &str = "colour, quantisation and output";
const WORDS: &str = "scene and camera read from their words";
const BUILD: &str = "scene build and range proof";

/// Roots, quotients and unit vectors out of line: called, not inlined into a phase.
const ARITHMETIC: &str = "roots, quotients and unit vectors (out of line)";

/// Where what no phase claims goes: start-up, and `core`'s functions left out of line.
const OTHER: &str = "other (start-up, core library)";

/// The phase a function called `name` (demangled, without its hash) marks, if any.
fn marked(name: &str) -> Option<&'static str> {
    core_phase(name).or_else(|| {
        PHASES
            .iter()
            .find(|phase| phase.marks.iter().any(|mark| name.contains(mark)))
            .map(|phase| phase.name)
    })
}

/// The phase of a function of the core called `name`: a function's own ([`FUNCTIONS`]), or
/// the one the module of the trait it implements declares, or its type's or its own module's;
/// `None` for a function outside the core, or of a helper's module.
///
/// [`FUNCTIONS`]: obscura::phase::FUNCTIONS
fn core_phase(name: &str) -> Option<&'static str> {
    use obscura::phase::{self, Phase as Declared};
    let symbol = Symbol::parse(name);
    let own = phase::module_of_path(&symbol.path);
    let of_trait = symbol.trait_path.as_deref().and_then(phase::module_of_path);
    if own.is_none() && of_trait.is_none() {
        return None;
    }
    let declared = phase::FUNCTIONS
        .iter()
        .find(|(function, _)| *function == symbol.function)
        .map(|&(_, phase)| phase)
        .or_else(|| of_trait.and_then(|module| module.phase))
        .or_else(|| own.and_then(|module| module.phase))?;
    match declared {
        Declared::Camera => Some(CAMERA),
        Declared::Tests => Some(TESTS),
        Declared::ShadowRays => Some(SHADOW_RAYS),
        Declared::SecondaryRays => Some(SECONDARY_RAYS),
        Declared::Shading | Declared::Cones => Some(SHADING),
        Declared::Arithmetic => Some(ARITHMETIC),
        Declared::Output => Some(OUTPUT),
        Declared::Words => Some(WORDS),
        Declared::Build => Some(BUILD),
        // A few operations a row: the work of the pixel loop around it.
        Declared::Culling => None,
    }
}

/// A function's demangled name as [`core_phase`] reads it, generic arguments left out: the
/// path of its module or type (for `<T as Trait>::f`, T's, then `::f`), the trait it
/// implements, and its own name.
#[derive(Debug, PartialEq, Eq)]
struct Symbol {
    path: String,
    trait_path: Option<String>,
    function: String,
}

impl Symbol {
    fn parse(name: &str) -> Self {
        let (path, trait_path) = match name.strip_prefix('<').and_then(|inner| {
            let end = closing(inner)?;
            Some((inner.get(..end)?, inner.get(end + 1..)?))
        }) {
            Some((qualified, rest)) => {
                let qualified = without_generics(qualified);
                let (of_type, of_trait) = match qualified.split_once(" as ") {
                    Some((of_type, of_trait)) => (of_type.to_owned(), Some(of_trait.to_owned())),
                    None => (qualified, None),
                };
                (format!("{of_type}{}", without_generics(rest)), of_trait)
            }
            None => (without_generics(name), None),
        };
        let function = path.rsplit("::").next().unwrap_or_default().to_owned();
        Self {
            path,
            trait_path,
            function,
        }
    }
}

/// Where the `<` that `text` follows closes: the index of its `>`.
fn closing(text: &str) -> Option<usize> {
    let mut depth = 1_usize;
    let mut previous = ' ';
    for (i, c) in text.char_indices() {
        match c {
            '<' => depth += 1,
            // `->`, of a function type, closes nothing.
            '>' if previous != '-' => {
                depth -= 1;
                if depth == 0 {
                    return Some(i);
                }
            }
            _ => {}
        }
        previous = c;
    }
    None
}

/// `text` without what its `<…>` enclose.
fn without_generics(text: &str) -> String {
    let mut depth = 0_usize;
    let mut previous = ' ';
    let mut out = String::new();
    for c in text.chars() {
        match c {
            '<' => depth += 1,
            '>' if previous != '-' => depth = depth.saturating_sub(1),
            _ if depth == 0 => out.push(c),
            _ => {}
        }
        previous = c;
    }
    out
}

/// The phase of an address whose functions are `inlined`, innermost first and the function
/// that holds it last.
fn phase_of<'a>(inlined: impl IntoIterator<Item = &'a str>) -> &'static str {
    let mut arithmetic = false;
    for name in inlined {
        match marked(name) {
            Some(ARITHMETIC) => arithmetic = true,
            Some(phase) => return phase,
            None => {}
        }
    }
    if arithmetic { ARITHMETIC } else { OTHER }
}

/// A function of the image: where it starts, how many bytes it spans, its demangled name.
#[derive(Clone, Debug, PartialEq, Eq)]
struct Function {
    start: u64,
    size: u64,
    name: String,
}

/// The functions of the ELF image `data`, by address (Thumb's mode bit cleared).
fn functions(data: &[u8]) -> Result<Vec<Function>> {
    let file = object::File::parse(data).context("the firmware image is not an ELF file")?;
    let mut functions: Vec<Function> = file
        .symbols()
        .filter(|symbol| symbol.kind() == SymbolKind::Text && symbol.size() > 0)
        .filter_map(|symbol| {
            let name = symbol.name().ok()?;
            Some(Function {
                start: symbol.address() & !1,
                size: symbol.size(),
                name: addr2line::demangle_auto(name.into(), None).into_owned(),
            })
        })
        .collect();
    functions.sort_by_key(|f| f.start);
    Ok(functions)
}

/// The entries of the firmware's frame markers, `obscura_frame_begins` and
/// `obscura_frame_ends` (`boards/qemu`), which the plugin counts each frame between.
pub fn frame_markers(elf: &Path) -> Result<(u64, u64)> {
    let data = std::fs::read(elf).with_context(|| format!("cannot read {}", elf.display()))?;
    let functions = functions(&data)?;
    let entry = |name: &str| {
        functions
            .iter()
            .find(|f| f.name == name)
            .map(|f| f.start)
            .with_context(|| format!("{} has no function `{name}`", elf.display()))
    };
    Ok((entry("obscura_frame_begins")?, entry("obscura_frame_ends")?))
}

/// The function holding `address`, if any.
fn holding(functions: &[Function], address: u64) -> Option<&Function> {
    let after = functions.partition_point(|f| f.start <= address);
    functions
        .get(after.checked_sub(1)?)
        .filter(|f| address < f.start + f.size)
}

/// An address that ran: how often, the function holding it (or the address, where no symbol
/// covers it) and the functions inlined there, innermost first (empty without debug
/// information).
#[derive(Clone, Debug)]
struct Executed {
    times: u64,
    function: String,
    inlined: Vec<String>,
}

/// Instructions executed, by function and by phase.
#[derive(Debug, Default)]
pub struct Profile {
    /// Per function of the image (its name, or the address for code no symbol covers), most
    /// first: what runs out of line.
    pub functions: Vec<(String, u64)>,
    /// Per function of the source: the innermost function inlined at each address (the
    /// image's function where nothing is), most first.
    pub sources: Vec<(String, u64)>,
    /// Per phase, in [`PHASES`]' order then [`OTHER`]; a phase that ran nothing is left out.
    pub phases: Vec<(&'static str, u64)>,
    /// Every instruction the run executed.
    pub total: u64,
    /// Bytes of the image's code per phase, each halfword by the functions inlined there as an
    /// executed address is, in [`PHASES`]' order then [`OTHER`]: what each part of the tracer
    /// costs in flash, whether it ran or not.
    pub code_bytes: Vec<(&'static str, u64)>,
}

impl Profile {
    /// Sums what `executed` by function and by phase.
    fn attribute(executed: &[Executed]) -> Self {
        let mut by_function: HashMap<&str, u64> = HashMap::new();
        let mut by_source: HashMap<&str, u64> = HashMap::new();
        let mut by_phase: HashMap<&str, u64> = HashMap::new();
        for e in executed {
            *by_function.entry(&e.function).or_default() += e.times;
            let source = e.inlined.first().unwrap_or(&e.function);
            *by_source.entry(source).or_default() += e.times;
            let inlined = e.inlined.iter().chain([&e.function]).map(String::as_str);
            *by_phase.entry(phase_of(inlined)).or_default() += e.times;
        }
        let phases = in_phase_order(&by_phase);
        Self {
            total: executed.iter().map(|e| e.times).sum(),
            functions: most_first(by_function),
            sources: most_first(by_source),
            phases,
            code_bytes: Vec::new(),
        }
    }

    /// The profile of a run of the image `elf` whose plugin counted `counts`.
    pub fn read(elf: &Path, counts: &Counts) -> Result<Self> {
        let data = std::fs::read(elf).with_context(|| format!("cannot read {}", elf.display()))?;
        let functions = functions(&data)?;
        let debug = Loader::new(elf).map_err(|e| {
            anyhow!(
                "cannot read the debug information of {}: {e}",
                elf.display()
            )
        })?;
        let inlined_at = |address: u64| -> Result<Vec<String>> {
            let mut inlined = Vec::new();
            let mut frames = debug
                .find_frames(address)
                .map_err(|e| anyhow!("the debug information at {address:#x}: {e}"))?;
            while let Some(frame) = frames
                .next()
                .map_err(|e| anyhow!("the debug information at {address:#x}: {e}"))?
            {
                if let Some(name) = frame.function.as_ref().and_then(|f| f.demangle().ok()) {
                    inlined.push(name.into_owned());
                }
            }
            Ok(inlined)
        };
        let executed = counts
            .run
            .iter()
            .map(|(&address, count)| {
                let times = count.executed;
                let function = holding(&functions, address)
                    .map_or_else(|| format!("{address:#x}"), |f| f.name.clone());
                Ok(Executed {
                    times,
                    function,
                    inlined: inlined_at(address)?,
                })
            })
            .collect::<Result<Vec<_>>>()?;
        // Thumb code is in halfwords: each is attributed as an executed address would be.
        let mut by_phase: HashMap<&str, u64> = HashMap::new();
        for function in &functions {
            for address in (function.start..function.start + function.size).step_by(2) {
                let inlined = inlined_at(address)?;
                let names = inlined
                    .iter()
                    .map(String::as_str)
                    .chain([function.name.as_str()]);
                *by_phase.entry(phase_of(names)).or_default() += 2;
            }
        }
        Ok(Self {
            code_bytes: in_phase_order(&by_phase),
            ..Self::attribute(&executed)
        })
    }
}

/// The phases of `by_phase`, in [`PHASES`]' order then [`OTHER`]; one without a count is left
/// out.
fn in_phase_order(by_phase: &HashMap<&str, u64>) -> Vec<(&'static str, u64)> {
    PHASES
        .iter()
        .map(|phase| phase.name)
        .chain([OTHER])
        .filter_map(|phase| Some((phase, *by_phase.get(phase)?)))
        .collect()
}

/// The counts of `by_name`, most first (ties by name).
fn most_first(by_name: HashMap<&str, u64>) -> Vec<(String, u64)> {
    let mut all: Vec<(String, u64)> = by_name
        .into_iter()
        .map(|(name, times)| (name.to_owned(), times))
        .collect();
    all.sort_by(|a, b| b.1.cmp(&a.1).then_with(|| a.0.cmp(&b.0)));
    all
}

/// What QEMU's plugin counted in a run (`host/qemu/profile.c`): each instruction translated,
/// and how often each ran and passed control elsewhere, in the whole run and in each frame
/// (between the firmware's frame markers), an address translated twice counted once.
#[derive(Debug, Default)]
pub struct Counts {
    /// The instructions at each address, as QEMU disassembled them for `core`.
    pub instructions: BTreeMap<u64, Instruction>,
    /// The whole run.
    pub run: BTreeMap<u64, Count>,
    /// Each frame, in the order drawn.
    pub frames: Vec<BTreeMap<u64, Count>>,
}

impl Counts {
    /// Reads the plugin's file at `path`, its instructions disassembled for `core`.
    pub fn read(path: &Path, core: Core) -> Result<Self> {
        let text = std::fs::read_to_string(path)
            .with_context(|| format!("the counting plugin wrote no {}", path.display()))?;
        Self::parse(&text, core)
    }

    /// Parses the plugin's lines: `insn ADDRESS BYTES TEXT`, `run ADDRESS EXECUTED TAKEN` and
    /// `frame N ADDRESS EXECUTED TAKEN` (addresses in hex, frames from 1).
    fn parse(text: &str, core: Core) -> Result<Self> {
        let mut counts = Self::default();
        for (i, line) in text.lines().enumerate() {
            let parsed = (|| -> Option<()> {
                let (kind, rest) = line.split_once(' ')?;
                let mut fields = rest.splitn(if kind == "insn" { 3 } else { 4 }, ' ');
                let mut next = || fields.next();
                let hex = |s: &str| u64::from_str_radix(s, 16).ok();
                match kind {
                    "insn" => {
                        let address = hex(next()?)?;
                        let size = next()?.parse().ok()?;
                        let text = next().unwrap_or("");
                        counts
                            .instructions
                            .insert(address, Instruction::parse(text, size, core));
                    }
                    "run" | "frame" => {
                        let map = if kind == "run" {
                            &mut counts.run
                        } else {
                            let n: usize = next()?.parse().ok()?;
                            if n == 0 || n > counts.frames.len() + 1 {
                                return None;
                            }
                            if n > counts.frames.len() {
                                counts.frames.push(BTreeMap::new());
                            }
                            counts.frames.get_mut(n - 1)?
                        };
                        let address = hex(next()?)?;
                        let executed: u64 = next()?.parse().ok()?;
                        let taken: u64 = next()?.parse().ok()?;
                        let count: &mut Count = map.entry(address).or_default();
                        count.executed += executed;
                        count.taken += taken;
                    }
                    _ => return None,
                }
                Some(())
            })();
            parsed.with_context(|| format!("line {} of the plugin's counts: `{line}`", i + 1))?;
        }
        Ok(counts)
    }
}

/// The plugin's source, in the workspace.
fn plugin_source() -> PathBuf {
    workspace().join("host/qemu/profile.c")
}

/// Builds the counting plugin with the system's C compiler (`cc`, or `$CC`) unless it is
/// newer than its source, and returns its path.
pub fn plugin() -> Result<PathBuf> {
    let source = plugin_source();
    let out = workspace().join("target/qemu-plugin");
    let library = out.join("profile.so");
    let modified = |path: &Path| std::fs::metadata(path).and_then(|m| m.modified()).ok();
    if let (Some(built), Some(written)) = (modified(&library), modified(&source))
        && built >= written
    {
        return Ok(library);
    }
    std::fs::create_dir_all(&out).with_context(|| format!("cannot create {}", out.display()))?;
    let cc = std::env::var_os("CC").unwrap_or_else(|| "cc".into());
    let status = Command::new(&cc)
        .args(["-shared", "-fPIC", "-O2", "-Wall", "-Werror", "-o"])
        .arg(&library)
        .arg(&source)
        .status()
        .with_context(|| {
            format!(
                "cannot run the C compiler `{}` to build QEMU's counting plugin; install one \
                 (sudo apt-get install gcc) or name it in $CC",
                cc.to_string_lossy()
            )
        })?;
    if !status.success() {
        bail!(
            "building QEMU's counting plugin {} failed (see the compiler's messages above)",
            source.display()
        );
    }
    Ok(library)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_symbol_is_read_without_its_generic_arguments() {
        let symbol = |path: &str, trait_path: Option<&str>, function: &str| Symbol {
            path: path.to_owned(),
            trait_path: trait_path.map(str::to_owned),
            function: function.to_owned(),
        };
        assert_eq!(
            Symbol::parse("obscura::shape::sphere::Sphere<S>::intersect"),
            symbol(
                "obscura::shape::sphere::Sphere::intersect",
                None,
                "intersect"
            )
        );
        assert_eq!(
            Symbol::parse("<obscura::scene::Scene<S,_,_,_> as obscura::words::Words>::take"),
            symbol(
                "obscura::scene::Scene::take",
                Some("obscura::words::Words"),
                "take"
            )
        );
        assert_eq!(
            Symbol::parse("obscura::render::trace_into<F, impl Fn(u32) -> bool>::{{closure}}"),
            symbol(
                "obscura::render::trace_into::{{closure}}",
                None,
                "{{closure}}"
            )
        );
        assert_eq!(Symbol::parse("Reset"), symbol("Reset", None, "Reset"));
    }

    #[test]
    fn an_address_belongs_to_the_innermost_phase_inlined_there() {
        for (inlined, phase) in [
            (
                &["obscura::camera::Camera<S>::row"][..],
                "primary rays (camera)",
            ),
            (
                &[
                    "<obscura::scalar::fixed_point::Fx<F,O> as core::ops::arith::Mul>::mul",
                    "obscura::shape::sphere::Sphere<S>::intersect",
                    "obscura::shade::Tracer<S>::nearest",
                    "obscura::shade::Tracer<S>::transmittance",
                    "obscura::shade::Tracer<S>::trace",
                    "obscura_firmware::frames::draw",
                ],
                "intersection tests",
            ),
            (
                &[
                    "obscura::shade::Tracer<S>::transmittance",
                    "obscura::shade::Tracer<S>::trace",
                ],
                "shadow rays (but their intersection tests)",
            ),
            (
                &[
                    "obscura::vec3::Vec3<S>::dot",
                    "obscura::shade::Tracer<S>::trace",
                ],
                "shading",
            ),
            (
                &["<obscura::scalar::fixed_point::Fx<F,O> as obscura::scalar::Scalar>::normalize3"],
                ARITHMETIC,
            ),
            (
                &["compiler_builtins::float::mul::__muldf3"],
                "compiler library (soft float, 64-bit division, copies)",
            ),
            (
                &[
                    "obscura::color::Rgb<S>::quantize_at",
                    "obscura_firmware::frames::draw",
                ],
                "colour, quantisation and output",
            ),
            (
                &["obscura::scene::range::check"],
                "scene build and range proof",
            ),
            (
                &[
                    "<obscura::scene::Scene<S,_,_,_> as obscura::words::Words>::take",
                    "obscura::scene::Scene<S,_,_,_>::from_words",
                ],
                "scene and camera read from their words",
            ),
            (&["Reset"], OTHER),
            (
                &[
                    "<core::iter::adapters::zip::Zip<A,B> as core::iter::adapters::zip::ZipImpl<A,B>>::next",
                ],
                OTHER,
            ),
        ] {
            assert_eq!(phase_of(inlined.iter().copied()), phase, "{inlined:?}");
        }
    }

    #[test]
    fn addresses_count_for_their_function_and_phase() {
        let function = |start, size, name: &str| Function {
            start,
            size,
            name: name.to_owned(),
        };
        let functions = [
            function(0x100, 0x20, "obscura::shape::sphere::Sphere<S>::intersect"),
            function(0x120, 0x10, "obscura::camera::Camera<S>::row"),
            function(0x200, 0x08, "__aeabi_lmul"),
        ];
        assert_eq!(holding(&functions, 0x100).unwrap().start, 0x100);
        assert_eq!(holding(&functions, 0x12f).unwrap().start, 0x120);
        assert!(holding(&functions, 0x130).is_none());
        assert!(holding(&functions, 0xff).is_none());
        let executed = |times, function: &str, inlined: &[&str]| Executed {
            times,
            function: function.to_owned(),
            inlined: inlined.iter().map(|&s| s.to_owned()).collect(),
        };
        let profile = Profile::attribute(&[
            executed(5, "obscura::shape::sphere::Sphere<S>::intersect", &[]),
            executed(
                7,
                "obscura::shape::sphere::Sphere<S>::intersect",
                &["obscura::vec3::Vec3<S>::dot"],
            ),
            executed(3, "obscura::camera::Camera<S>::row", &[]),
            executed(4, "0x130", &[]),
            executed(10, "__aeabi_lmul", &[]),
        ]);
        assert_eq!(profile.total, 29);
        assert_eq!(
            profile.functions,
            [
                (
                    "obscura::shape::sphere::Sphere<S>::intersect".to_owned(),
                    12
                ),
                ("__aeabi_lmul".to_owned(), 10),
                ("0x130".to_owned(), 4),
                ("obscura::camera::Camera<S>::row".to_owned(), 3),
            ]
        );
        assert_eq!(
            profile.sources[..2],
            [
                ("__aeabi_lmul".to_owned(), 10),
                ("obscura::vec3::Vec3<S>::dot".to_owned(), 7),
            ]
        );
        assert_eq!(
            profile.phases,
            [
                ("primary rays (camera)", 3),
                ("intersection tests", 12),
                ("compiler library (soft float, 64-bit division, copies)", 10),
                (OTHER, 4),
            ]
        );
    }

    #[test]
    fn malformed_counts_name_their_line() {
        let error = Counts::parse("run 100 3 0\nrun zz 1 0\n", Core::CortexM4).unwrap_err();
        assert!(format!("{error:#}").contains("line 2"), "{error:#}");
        let counts = Counts::parse(
            "insn 1a 2 adds r0, r1\nrun 1a 3 0\nframe 1 1a 2 0\nframe 2 1a 1 1\nrun 1a 1 0\n",
            Core::CortexM4,
        )
        .unwrap();
        assert_eq!(
            counts.run[&0x1a],
            Count {
                executed: 4,
                taken: 0
            }
        );
        assert_eq!(counts.frames.len(), 2);
        assert_eq!(
            counts.frames[1][&0x1a],
            Count {
                executed: 1,
                taken: 1
            }
        );
        assert_eq!(counts.instructions[&0x1a].size, 2);
        let skipped = Counts::parse("frame 2 1a 1 1\n", Core::CortexM4).unwrap_err();
        assert!(format!("{skipped:#}").contains("line 1"), "{skipped:#}");
    }
}
