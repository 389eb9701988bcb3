//! The scenes the harness takes: a built-in one by name, or a TOML scene file (see
//! `host/scenes/` and the README's "Scene files"). A file is only read and parsed here; the
//! core's scene build then checks what it says.

use crate::owned::OwnedScene;
use anyhow::{Context, Result, bail};
use obscura::scenes;
use std::path::Path;

/// A scene and what to call it.
#[derive(Clone, Debug)]
pub struct NamedScene {
    /// The built-in scene's name, or the file's stem.
    pub name: String,
    /// The description.
    pub scene: OwnedScene,
}

/// The built-in scene called `name`, or else the scene file at that path.
///
/// # Errors
/// When it is neither, or the file cannot be read or is not a scene.
pub fn load(name: &str) -> Result<NamedScene> {
    if let Some(built_in) = scenes::find(name) {
        return Ok(NamedScene {
            name: built_in.name.to_owned(),
            scene: OwnedScene::from_desc(&built_in.desc),
        });
    }
    let path = Path::new(name);
    if !path.is_file() {
        let names: Vec<_> = scenes::BUILT_IN.iter().map(|s| s.name).collect();
        bail!(
            "there is no scene `{name}`: give a built-in scene ({}) or a scene file (see \
             host/scenes/)",
            names.join(", ")
        );
    }
    let text =
        std::fs::read_to_string(path).with_context(|| format!("cannot read {}", path.display()))?;
    let scene = parse(&text).with_context(|| format!("{} is not a scene file", path.display()))?;
    Ok(NamedScene {
        name: path.file_stem().map_or_else(
            || name.to_owned(),
            |stem| stem.to_string_lossy().into_owned(),
        ),
        scene,
    })
}

/// Parses the TOML text of a scene file.
///
/// # Errors
/// TOML's own, which say where in the text and what was expected.
pub fn parse(text: &str) -> Result<OwnedScene> {
    Ok(toml::from_str(text)?)
}

#[cfg(test)]
mod tests {
    use super::*;
    use obscura::{BackgroundDesc, MaterialDesc, ShapeDesc};

    const MINIMAL: &str = r#"
        far = 20.0
        camera = { eye = [0.0, 1.0, -5.0], look_at = [0.0, 1.0, 0.0], up = [0.0, 1.0, 0.0], vfov_degrees = 50.0 }

        [[objects]]
        shape.sphere = { center = [0.0, 1.0, 0.0], radius = 1.0 }
        material = { colour = [0.9, 0.2, 0.1], specular = 0.4, shininess = 30 }

        [[objects]]
        shape.plane = { point = [0.0, 0.0, 0.0], normal = [0.0, 1.0, 0.0], checker = { colour = [0.1, 0.1, 0.1], size = 1.0 } }

        [[lights]]
        position = [-3.0, 6.0, -4.0]
        colour = [1.0, 1.0, 1.0]
    "#;

    #[test]
    fn a_minimal_file_fills_in_the_defaults() {
        let scene = parse(MINIMAL).expect("parses");
        assert_eq!(scene.objects.len(), 2);
        assert_eq!(scene.max_depth, 5);
        assert_eq!(scene.background, BackgroundDesc::Solid([0.0; 3]));
        let material = scene.objects[0].material;
        assert_eq!(material.colour, [0.9, 0.2, 0.1]);
        assert_eq!(material.shininess, 30);
        // What it does not say is the default matte material's.
        assert_eq!(material.diffuse, MaterialDesc::default().diffuse);
        assert_eq!(scene.objects[1].material, MaterialDesc::default());
        assert!(matches!(
            scene.objects[1].shape,
            ShapeDesc::Plane {
                checker: Some(_),
                ..
            }
        ));
    }

    #[test]
    fn mistakes_are_named_with_their_place() {
        let typo = MINIMAL.replace("radius", "radios");
        let error = format!("{:#}", parse(&typo).expect_err("an unknown field"));
        assert!(
            error.contains("radios") && error.contains("line"),
            "{error}"
        );
        let missing = MINIMAL.replace("far = 20.0", "");
        let error = format!("{:#}", parse(&missing).expect_err("far is required"));
        assert!(error.contains("far"), "{error}");
        let shape = MINIMAL.replace("shape.sphere", "shape.cube");
        let error = format!("{:#}", parse(&shape).expect_err("no cubes"));
        assert!(
            error.contains("cube") && error.contains("sphere"),
            "{error}"
        );
    }

    #[test]
    fn a_name_is_a_built_in_scene_or_a_file() {
        assert_eq!(load("whitted").expect("built in").name, "whitted");
        let error = format!("{:#}", load("no-such-scene").expect_err("neither"));
        assert!(
            error.contains("whitted") && error.contains("scene file"),
            "{error}"
        );
    }
}
