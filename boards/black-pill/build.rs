//! Links with cortex-m-rt's `link.x`, which includes the workspace's `memory.x` (the firmware
//! crate's build script puts it on the linker's path): the STM32F411's map.

fn main() {
    println!("cargo::rerun-if-changed=build.rs");
    println!("cargo::rustc-link-arg-bins=-Tlink.x");
}
