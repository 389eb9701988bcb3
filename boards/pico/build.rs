//! Links with cortex-m-rt's `link.x`, which includes the workspace's `memory.x` (the firmware
//! crate's build script puts it on the linker's path), and takes its RP2040 map: 2 MiB of
//! flash after the 256-byte boot loader, 256 KiB of RAM.

fn main() {
    println!("cargo::rerun-if-changed=build.rs");
    println!("cargo::rustc-link-arg-bins=--defsym=__rp2040=1");
    println!("cargo::rustc-link-arg-bins=-Tlink.x");
}
