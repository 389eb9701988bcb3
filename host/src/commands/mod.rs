//! One module per subcommand; this one dispatches and holds what they share.

mod bench;
mod compare;
mod firmware;
mod render;

use crate::cli::Command;
use anyhow::{Result, bail};
use obscura::scenes::{self, BuiltIn};

/// Runs a subcommand.
pub fn run(command: Command) -> Result<()> {
    match command {
        Command::Scenes => {
            for scene in &scenes::BUILT_IN {
                println!("{:10} {}", scene.name, scene.summary);
            }
            Ok(())
        }
        Command::Render(args) => render::run(&args),
        Command::Compare(args) => compare::run(&args),
        Command::Bench(args) => bench::run(&args),
        Command::Firmware(args) => firmware::run(&args),
    }
}

/// The built-in scene called `name`, or an error that lists the names there are.
pub fn scene(name: &str) -> Result<&'static BuiltIn> {
    match scenes::find(name) {
        Some(scene) => Ok(scene),
        None => {
            let names: Vec<_> = scenes::BUILT_IN.iter().map(|s| s.name).collect();
            bail!(
                "there is no scene `{name}`; the built-in scenes are: {}",
                names.join(", ")
            )
        }
    }
}

/// Writes a PNG, saying which file could not be written.
pub fn save(image: &image::RgbImage, path: &std::path::Path) -> Result<()> {
    use anyhow::Context;
    image
        .save(path)
        .with_context(|| format!("cannot write {}", path.display()))
}
