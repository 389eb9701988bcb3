//! A scene from a file, or from TOML text, built in a format: what the harness and the
//! firmware's build do with a scene file. A refusal is placed at the file's line and column.
//!
//! `cargo run -p obscura-scene --example load_scene -- host/scenes/ball.toml`

use obscura::{I16F16, Scene, ShapeDesc};
use obscura_scene::{HostScene, error_text};
use std::path::Path;

/// The file (or built-in scene) named, built in 16.16 fixed point.
fn build(name: &str) -> anyhow::Result<()> {
    let named = obscura_scene::load(name)?;
    let desc = named.scene.desc();
    HostScene::<I16F16>::build(&desc).map_err(|refusal| named.locate(refusal.into()))?;
    let spheres = desc
        .objects
        .iter()
        .filter(|object| matches!(object.shape, ShapeDesc::Sphere { .. }))
        .count();
    println!(
        "{}: {} objects ({spheres} spheres), {} lights, a world {} across; i16f16 holds it",
        named.name,
        desc.objects.len(),
        desc.lights.len(),
        2.0 * desc.far
    );
    Ok(())
}

/// A scene given as TOML text: a ball under a light, with no floor.
fn from_text() -> anyhow::Result<()> {
    let text = r#"
        far = 10.0
        [camera]
        eye = [0.0, 1.0, -4.0]
        look_at = [0.0, 1.0, 0.0]
        up = [0.0, 1.0, 0.0]
        vfov_degrees = 40.0
        [[objects]]
        shape.sphere = { center = [0.0, 1.0, 0.0], radius = 1.0 }
        [[lights]]
        position = [2.0, 4.0, -3.0]
        colour = [1.0, 1.0, 1.0]
    "#;
    let owned = obscura_scene::parse(Path::new("text.toml"), text)?;
    let scene = Scene::<f32, 4, 2, 6>::build(&owned.desc())?;
    println!("text.toml: {} objects, built in f32", scene.objects().len());
    Ok(())
}

fn main() {
    let name = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "host/scenes/ball.toml".to_owned());
    if let Err(error) = build(&name).and_then(|()| from_text()) {
        eprintln!("{}", error_text(&error));
        std::process::exit(1);
    }
}
