//! The phases of a frame's work as the core's own modules declare them: each module says which
//! phase the work it does belongs to (`declare_phase!`), and [`FUNCTIONS`] names the few
//! functions whose work is a phase of its own. The workspace's tools read them here, the
//! operation counter by the source file an operation is formed in and the firmware's profile
//! by the functions inlined at an address, so that no tool names the core's files or
//! functions, and a module that moves takes its phase along (its file and path are the
//! compiler's, `file!()` and `module_path!()`).

/// A phase of a frame's work.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Phase {
    /// Primary rays: the camera.
    Camera,
    /// Object tests, and a mesh's hierarchy walked and read.
    Tests,
    /// Which objects a shadow ray tests: their cones from each light.
    Cones,
    /// Shading: lights, materials, and a surface's point, normal and pattern once its test is
    /// over.
    Shading,
    /// Shadow rays, but their tests: a function's phase, within shading.
    ShadowRays,
    /// Reflected and refracted rays set up: a function's phase, within shading.
    SecondaryRays,
    /// The pixel loop, samples averaged, colours quantised and sent to the display.
    Output,
    /// Which objects a row's primary rays can meet: a few operations a row.
    Culling,
    /// A proven scene and camera read back from their words.
    Words,
    /// The scene's build and range proof, and what never runs in a frame.
    Build,
    /// Numbers and vectors: out of line, a phase of its own; inlined, and in a count of
    /// operations, the work of the phase that called them.
    Arithmetic,
}

/// A module of the core and the phase of its work: `None` for a helper (a ray, a sample
/// pattern) whose work is always its caller's.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Module {
    /// Its source file, as `file!()` and `core::panic::Location` give it.
    pub file: &'static str,
    /// Its path, as `module_path!()` gives it and a symbol's name begins.
    pub path: &'static str,
    /// Its phase.
    pub phase: Option<Phase>,
}

/// Declares the phase of the module it is written in: a constant `PHASE` that [`MODULES`]
/// lists.
macro_rules! declare_phase {
    ($phase:expr) => {
        /// The phase of this module's work ([`crate::phase`]).
        pub(crate) const PHASE: crate::phase::Module = crate::phase::Module {
            file: file!(),
            path: module_path!(),
            phase: $phase,
        };
    };
}
pub(crate) use declare_phase;

declare_phase!(Some(Phase::Build));

/// Every module of the core, with its phase (but the tests' helpers): listed at the crate
/// root, which every module descends from.
pub const MODULES: &[Module] = crate::MODULE_PHASES;

/// The functions whose work is a phase of its own, whichever module holds them, by name.
pub const FUNCTIONS: [(&str, Phase); 4] = [
    ("transmittance", Phase::ShadowRays),
    ("spawn", Phase::SecondaryRays),
    ("from_words", Phase::Words),
    ("from_proven", Phase::Words),
];

/// The module of the core whose source file is `file`, if any.
#[must_use]
pub fn module_of_file(file: &str) -> Option<&'static Module> {
    MODULES.iter().find(|module| module.file == file)
}

/// The module of the core at the start of the path `path` (a function's or a type's, as a
/// symbol names it, without generic arguments): the longest module path it begins with.
#[must_use]
pub fn module_of_path(path: &str) -> Option<&'static Module> {
    MODULES
        .iter()
        .filter(|module| {
            path.strip_prefix(module.path)
                .is_some_and(|rest| rest.is_empty() || rest.starts_with("::"))
        })
        .max_by_key(|module| module.path.len())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    /// Every `.rs` file under `directory`, as the compiler names it (`src/…`).
    fn sources(directory: &Path, files: &mut Vec<String>) {
        for entry in std::fs::read_dir(directory).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                sources(&path, files);
            } else if path.extension().is_some_and(|e| e == "rs") {
                let root = Path::new(env!("CARGO_MANIFEST_DIR"));
                let relative = path.strip_prefix(root).unwrap();
                files.push(relative.to_string_lossy().replace('\\', "/"));
            }
        }
    }

    #[test]
    fn every_module_declares_its_phase_once() {
        let mut files = Vec::new();
        sources(&Path::new(env!("CARGO_MANIFEST_DIR")).join("src"), &mut files);
        files.retain(|file| file != "src/test_util.rs");
        files.sort();
        let mut declared: Vec<String> = MODULES
            .iter()
            .map(|module| module.file.replace('\\', "/"))
            .collect();
        declared.sort();
        assert_eq!(declared, files);
        assert_eq!(module_of_file(file!()), Some(&PHASE));
    }

    #[test]
    fn a_path_belongs_to_the_innermost_module_it_begins_with() {
        let phase = |path| module_of_path(path).and_then(|module| module.phase);
        assert_eq!(phase("obscura::shape::sphere::Sphere::intersect"), Some(Phase::Tests));
        assert_eq!(phase("obscura::shade::Tracer::trace"), Some(Phase::Shading));
        assert_eq!(phase("obscura::scalar::fixed_point::Fx"), Some(Phase::Arithmetic));
        assert_eq!(phase("obscura::ray::Ray::at"), None);
        assert_eq!(module_of_path("obscura::scenery"), module_of_path("obscura"));
        assert_eq!(module_of_path("obscura_firmware::frames::draw"), None);
    }

    #[test]
    fn every_function_with_a_phase_of_its_own_is_the_cores() {
        let mut files = Vec::new();
        sources(&Path::new(env!("CARGO_MANIFEST_DIR")).join("src"), &mut files);
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let text: String = files
            .iter()
            .map(|file| std::fs::read_to_string(root.join(file)).unwrap())
            .collect();
        for (name, _) in FUNCTIONS {
            assert!(text.contains(&format!("fn {name}(")), "no function {name}");
        }
    }
}
