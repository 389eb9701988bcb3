//! Tells the core which machine it is built for where Rust's own `cfg` does not: `armv6m` on the
//! Cortex-M0 and M0+ (thumbv6m), whose fixed-point products are built without `__aeabi_lmul`
//! (`src/scalar/kernels.rs`).

fn main() {
    println!("cargo::rerun-if-changed=build.rs");
    println!("cargo::rustc-check-cfg=cfg(armv6m)");
    if std::env::var("TARGET").is_ok_and(|target| target.starts_with("thumbv6m")) {
        println!("cargo::rustc-cfg=armv6m");
    }
}
