//! `obscura`: the desktop harness of the obscura ray tracer (`obscura_host::main`).

fn main() -> std::process::ExitCode {
    obscura_host::main()
}
