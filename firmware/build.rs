//! Configures the firmware from the environment (see `obscura_scene::firmware` and the README):
//! reads and proves its scenes in its formats with the core's own scene build, writes what it
//! draws to `$OUT_DIR/frames.rs`, and puts the workspace's `memory.x` on the linker's path for
//! the boards' binaries.

use obscura_scene::firmware;
use std::env;
use std::fs;
use std::path::{Path, PathBuf};

fn main() {
    let manifest = PathBuf::from(env::var_os("CARGO_MANIFEST_DIR").expect("cargo sets it"));
    let workspace = manifest.parent().unwrap_or(&manifest);
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    let target = env::var("TARGET").unwrap_or_default();
    println!("cargo::rerun-if-changed=build.rs");
    for name in firmware::variables() {
        println!("cargo::rerun-if-env-changed={name}");
    }
    match firmware::generate(workspace) {
        Ok(generated) => {
            for input in &generated.inputs {
                println!("cargo::rerun-if-changed={}", input.display());
            }
            fs::write(out.join("frames.rs"), generated.source).expect("OUT_DIR is writable");
        }
        Err(error) => {
            obscura_scene::build::fail(&error);
            return;
        }
    }
    if target.starts_with("thumbv") {
        link(workspace, &out);
    }
}

/// The memory map: `memory.x` copied next to the build's other outputs and put on the linker's
/// path, for the binaries under `boards/`, which depend on this crate (each hands the linker
/// cortex-m-rt's `link.x`, which includes it, and says which board's map to take).
fn link(workspace: &Path, out: &Path) {
    let map = workspace.join("memory.x");
    println!("cargo::rerun-if-changed={}", map.display());
    fs::copy(&map, out.join("memory.x")).expect("memory.x is readable");
    println!("cargo::rustc-link-search={}", out.display());
}
