//! Links for the architecture built for. On the Cortex-M33, with cortex-m-rt's `link.x`, which
//! includes the workspace's `memory.x` (the firmware crate's build script puts it on the
//! linker's path) and takes its RP2350 map (`__rp2350`); on Hazard3, with riscv-rt's `link.x`
//! after this crate's `rp2350-riscv.x`, which gives it the same map.

fn main() {
    println!("cargo::rerun-if-changed=build.rs");
    println!("cargo::rerun-if-changed=rp2350-riscv.x");
    let target = std::env::var("TARGET").unwrap_or_default();
    if target.starts_with("riscv32") {
        let here = std::env::var("CARGO_MANIFEST_DIR").unwrap_or_default();
        println!("cargo::rustc-link-search={here}");
        println!("cargo::rustc-link-arg-bins=-Trp2350-riscv.x");
    } else {
        println!("cargo::rustc-link-arg-bins=--defsym=__rp2350=1");
    }
    println!("cargo::rustc-link-arg-bins=-Tlink.x");
}
