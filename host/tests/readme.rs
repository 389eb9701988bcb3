//! The front page as a newcomer follows it: its scene is the one that ships, and its desktop
//! quick starts' `obscura` commands run as written (the boards' commands run in
//! `host/check.sh`, as far as a machine without a board can).

use std::path::Path;
use std::process::Command;

const README: &str = include_str!("../../README.md");

/// The bodies of the front page's code blocks of `language` under the heading `heading`.
fn blocks(heading: &str, language: &str) -> Vec<String> {
    let section = README
        .split("\n## ")
        .find(|section| section.starts_with(heading))
        .unwrap_or_else(|| panic!("the README has no section {heading:?}"));
    let fence = format!("```{language}\n");
    section
        .split(&fence)
        .skip(1)
        .map(|rest| rest.split("```").next().unwrap_or_default().to_owned())
        .collect()
}

#[test]
fn the_front_pages_scene_is_the_one_that_ships() {
    let toml = blocks("Quick start: your own scene", "toml");
    let shipped = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/ball.toml"))
        .expect("host/scenes/ball.toml");
    assert_eq!(
        toml,
        [shipped],
        "paste host/scenes/ball.toml into the README, or the other way"
    );
}

#[test]
fn the_desktop_quick_starts_run_as_written() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("readme");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::copy(
        concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/ball.toml"),
        dir.join("ball.toml"),
    )
    .unwrap();
    // The camera path's scene, where the command names it from the workspace's root.
    std::fs::create_dir_all(dir.join("host/scenes")).unwrap();
    std::fs::copy(
        concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/orbit.toml"),
        dir.join("host/scenes/orbit.toml"),
    )
    .unwrap();
    let sections = ["Quick start: on the desktop", "Quick start: your own scene"];
    let commands: Vec<String> = sections
        .iter()
        .flat_map(|section| blocks(section, "sh"))
        .flat_map(|block| block.lines().map(str::to_owned).collect::<Vec<_>>())
        .map(|line| {
            line.split(" # ")
                .next()
                .unwrap_or_default()
                .trim()
                .to_owned()
        })
        .filter(|line| !line.is_empty())
        .collect();
    assert!(commands.len() >= 5, "{commands:?}");
    for command in &commands {
        let words: Vec<&str> = command.split_whitespace().collect();
        assert_eq!(words.first(), Some(&"obscura"), "{command}");
        let output = Command::new(env!("CARGO_BIN_EXE_obscura"))
            .args(&words[1..])
            .current_dir(&dir)
            .output()
            .expect("the binary runs");
        assert!(
            output.status.success(),
            "{command}: {}",
            String::from_utf8_lossy(&output.stderr)
        );
    }
    for written in [
        "out/whitted.png",
        "out/preview.png",
        "ball.png",
        "orbit.gif",
    ] {
        assert!(dir.join(written).is_file(), "{written}");
    }
}
