//! The workspace's layout, as the book draws it (`docs/design.md`): which crate uses which (its path
//! dependencies), and that no module of a crate imports in a circle.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("the harness is in the workspace")
        .to_path_buf()
}

/// The workspace crates a manifest names under `section` (`dependencies`,
/// `build-dependencies`, `dev-dependencies`), by their package names.
fn path_dependencies(manifest: &Path, section: &str) -> BTreeSet<String> {
    let text = fs::read_to_string(manifest).unwrap();
    let table: toml::Table = toml::from_str(&text).unwrap();
    table
        .get(section)
        .and_then(toml::Value::as_table)
        .map(|deps| {
            deps.iter()
                .filter(|(_, spec)| spec.get("path").is_some())
                .map(|(name, _)| name.clone())
                .collect()
        })
        .unwrap_or_default()
}

#[test]
fn each_crate_uses_the_crates_the_readme_draws_and_no_other() {
    let root = workspace();
    let set = |names: &[&str]| {
        names
            .iter()
            .map(|n| (*n).to_owned())
            .collect::<BTreeSet<_>>()
    };
    let expected = [
        ("Cargo.toml", "dependencies", set(&[])),
        ("scene/Cargo.toml", "dependencies", set(&["obscura"])),
        ("firmware/Cargo.toml", "dependencies", set(&["obscura"])),
        (
            "firmware/Cargo.toml",
            "build-dependencies",
            set(&["obscura-scene"]),
        ),
        (
            "host/Cargo.toml",
            "dependencies",
            set(&["obscura", "obscura-scene"]),
        ),
        (
            "boards/qemu/Cargo.toml",
            "dependencies",
            set(&["obscura", "obscura-firmware"]),
        ),
        (
            "boards/black-pill/Cargo.toml",
            "dependencies",
            set(&["obscura-firmware"]),
        ),
        (
            "boards/pico/Cargo.toml",
            "dependencies",
            set(&["obscura", "obscura-firmware"]),
        ),
    ];
    for (manifest, section, uses) in expected {
        assert_eq!(
            path_dependencies(&root.join(manifest), section),
            uses,
            "{manifest} [{section}]"
        );
    }
}

/// Each module of the crate whose sources are under `src` (its path from the crate root, `a::b`)
/// and its source without comments and tests.
fn modules(src: &Path) -> BTreeMap<String, String> {
    let mut found = BTreeMap::new();
    let mut dirs = vec![src.to_path_buf()];
    while let Some(dir) = dirs.pop() {
        for entry in fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                dirs.push(path);
                continue;
            }
            if path.extension().is_none_or(|e| e != "rs") {
                continue;
            }
            let relative = path.strip_prefix(src).unwrap().with_extension("");
            let mut parts: Vec<String> = relative
                .components()
                .map(|c| c.as_os_str().to_string_lossy().into_owned())
                .collect();
            if matches!(
                parts.last().map(String::as_str),
                Some("mod" | "lib" | "main")
            ) {
                parts.pop();
            }
            let text = fs::read_to_string(&path).unwrap();
            let code: String = text
                .split("#[cfg(test)]\nmod tests")
                .next()
                .unwrap_or_default()
                .lines()
                .filter(|line| !line.trim_start().starts_with("//"))
                .collect::<Vec<_>>()
                .join("\n");
            found.insert(parts.join("::"), code);
        }
    }
    found
}

/// The modules each module uses: every `crate::a::b` path in its code (within `use crate::{…}`
/// too) and every `super::x`, as the longest module it names, but its own and its ancestors
/// and descendants.
fn uses(modules: &BTreeMap<String, String>) -> BTreeMap<&str, BTreeSet<&str>> {
    let module_of = |path: &str| -> Option<&str> {
        let segments: Vec<&str> = path.split("::").collect();
        (1..=segments.len())
            .rev()
            .map(|k| segments[..k].join("::"))
            .find_map(|candidate| modules.get_key_value(&candidate).map(|(k, _)| k.as_str()))
    };
    let related = |a: &str, b: &str| {
        a == b || a.starts_with(&format!("{b}::")) || b.starts_with(&format!("{a}::"))
    };
    let mut graph = BTreeMap::new();
    for (module, code) in modules {
        let mut used = BTreeSet::new();
        let mut paths: Vec<String> = Vec::new();
        for (i, _) in code.match_indices("crate::") {
            let rest = &code[i + "crate::".len()..];
            if let Some(group) = rest.strip_prefix('{') {
                let inner = group.split('}').next().unwrap_or_default();
                paths.extend(inner.split(',').map(|item| {
                    item.trim()
                        .split([' ', '{'])
                        .next()
                        .unwrap_or_default()
                        .to_owned()
                }));
            } else {
                let path: String = rest
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_' || *c == ':')
                    .collect();
                paths.push(path);
            }
        }
        let parent = module.rsplit_once("::").map_or("", |(parent, _)| parent);
        for (i, _) in code.match_indices("super::") {
            let rest = &code[i + "super::".len()..];
            let name: String = rest
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            paths.push(if parent.is_empty() {
                name
            } else {
                format!("{parent}::{name}")
            });
        }
        for path in paths {
            if let Some(target) = module_of(path.trim_end_matches(':'))
                && !related(module, target)
            {
                used.insert(target);
            }
        }
        graph.insert(module.as_str(), used);
    }
    graph
}

/// A circle of imports, if the graph has one.
fn circle<'a>(graph: &BTreeMap<&'a str, BTreeSet<&'a str>>) -> Option<Vec<&'a str>> {
    // Depth first, colouring each module: on the path (1) or done (2).
    fn visit<'a>(
        module: &'a str,
        graph: &BTreeMap<&'a str, BTreeSet<&'a str>>,
        state: &mut BTreeMap<&'a str, u8>,
        path: &mut Vec<&'a str>,
    ) -> Option<Vec<&'a str>> {
        state.insert(module, 1);
        path.push(module);
        for &next in graph.get(module).into_iter().flatten() {
            match state.get(next) {
                Some(1) => {
                    let start = path.iter().position(|&m| m == next).unwrap_or(0);
                    let mut found = path[start..].to_vec();
                    found.push(next);
                    return Some(found);
                }
                Some(_) => {}
                None => {
                    if let Some(found) = visit(next, graph, state, path) {
                        return Some(found);
                    }
                }
            }
        }
        path.pop();
        state.insert(module, 2);
        None
    }
    let mut state = BTreeMap::new();
    for &module in graph.keys() {
        if !state.contains_key(module)
            && let Some(found) = visit(module, graph, &mut state, &mut Vec::new())
        {
            return Some(found);
        }
    }
    None
}

#[test]
fn no_module_imports_in_a_circle() {
    let root = workspace();
    for src in ["src", "scene/src", "host/src", "firmware/src"] {
        let modules = modules(&root.join(src));
        assert!(modules.len() > 3, "{src}: {} modules", modules.len());
        let graph = uses(&modules);
        assert_eq!(circle(&graph), None, "{src}: a circle of imports");
    }
}

#[test]
fn a_circle_is_found() {
    let modules: BTreeMap<String, String> = [
        ("a", "use crate::b::Thing;"),
        ("b", "use crate::{c::More, d};"),
        ("c", "fn f() { crate::a::g() }"),
        ("d", ""),
    ]
    .into_iter()
    .map(|(m, code)| (m.to_owned(), code.to_owned()))
    .collect();
    assert_eq!(circle(&uses(&modules)), Some(vec!["a", "b", "c", "a"]));
    let mut broken = modules.clone();
    broken.insert("c".to_owned(), "fn f() {}".to_owned());
    assert_eq!(circle(&uses(&broken)), None);
}
