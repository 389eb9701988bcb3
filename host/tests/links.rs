//! Every relative link of the front page and the book leads somewhere: to a file or directory
//! of the repository, and where it names an anchor (`#…`), to a heading of that page, as
//! GitHub names its headings' anchors. The book builds as an mdBook from `docs/` alone: its
//! chapters link only within `docs/`, and `docs/SUMMARY.md` lists each of them.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// The repository.
fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("the harness is in the workspace")
        .to_path_buf()
}

/// The front page and every page of the book.
fn pages() -> Vec<PathBuf> {
    let root = workspace();
    let mut pages = vec![root.join("README.md"), root.join("CHANGELOG.md")];
    let mut book: Vec<PathBuf> = std::fs::read_dir(root.join("docs"))
        .expect("docs/")
        .map(|entry| entry.expect("a directory entry").path())
        .filter(|path| path.extension().is_some_and(|e| e == "md"))
        .collect();
    book.sort();
    pages.extend(book);
    pages
}

/// `text`'s lines outside fenced code blocks and comments (such as the book's markers, whose
/// commands are not links).
fn prose(text: &str) -> Vec<&str> {
    let mut fenced = false;
    text.lines()
        .filter(|line| {
            if line.trim_start().starts_with("```") {
                fenced = !fenced;
                return false;
            }
            !fenced && !line.trim_start().starts_with("<!--")
        })
        .collect()
}

/// `line` without its code spans (`` `…` ``), where a link is not one.
fn without_code(line: &str) -> String {
    line.split('`').step_by(2).collect::<Vec<_>>().join(" ")
}

/// The anchor GitHub gives a heading: lower case, without punctuation but hyphens and
/// underscores, spaces as hyphens.
fn anchor(heading: &str) -> String {
    heading
        .trim()
        .chars()
        .flat_map(char::to_lowercase)
        .filter(|c| c.is_alphanumeric() || matches!(c, ' ' | '-' | '_'))
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

/// The anchors of the page `text`: each heading's, a repeated one numbered as GitHub numbers it.
fn anchors(text: &str) -> BTreeSet<String> {
    let mut found = BTreeSet::new();
    for line in prose(text) {
        let Some(heading) = line.strip_prefix('#') else {
            continue;
        };
        let base = anchor(heading.trim_start_matches('#'));
        let mut name = base.clone();
        let mut n = 0;
        while found.contains(&name) {
            n += 1;
            name = format!("{base}-{n}");
        }
        found.insert(name);
    }
    found
}

/// The relative links of the page `text` (`[…](target)`), but to other sites.
fn links(text: &str) -> Vec<String> {
    let mut found = Vec::new();
    for line in prose(text) {
        let line = without_code(line);
        let mut rest = line.as_str();
        while let Some(start) = rest.find("](") {
            let after = &rest[start + 2..];
            let Some(end) = after.find(')') else { break };
            let target = &after[..end];
            if !target.contains("://") && !target.starts_with("mailto:") {
                found.push(target.to_owned());
            }
            rest = &after[end..];
        }
    }
    found
}

#[test]
fn every_relative_link_and_anchor_resolves() {
    let mut broken = Vec::new();
    for page in pages() {
        let text = std::fs::read_to_string(&page).expect("a page");
        let directory = page.parent().expect("a page is in a directory");
        for link in links(&text) {
            let (path, fragment) = match link.split_once('#') {
                Some((path, fragment)) => (path, Some(fragment)),
                None => (link.as_str(), None),
            };
            let target = if path.is_empty() {
                page.clone()
            } else {
                directory.join(path)
            };
            let name = page.strip_prefix(workspace()).unwrap_or(&page).display();
            if !target.exists() {
                broken.push(format!("{name}: {link}: no such file"));
                continue;
            }
            let Some(fragment) = fragment else { continue };
            let Ok(target_text) = std::fs::read_to_string(&target) else {
                broken.push(format!("{name}: {link}: an anchor of what is not a page"));
                continue;
            };
            if !anchors(&target_text).contains(fragment) {
                broken.push(format!("{name}: {link}: no heading has that anchor"));
            }
        }
    }
    assert!(broken.is_empty(), "broken links:\n{}", broken.join("\n"));
}

#[test]
fn the_book_is_its_summarys_chapters_and_links_only_within_docs() {
    let docs = workspace().join("docs");
    let summary = std::fs::read_to_string(docs.join("SUMMARY.md")).expect("docs/SUMMARY.md");
    let listed: BTreeSet<String> = links(&summary).into_iter().collect();
    let mut wrong = Vec::new();
    for page in pages().iter().filter(|page| page.starts_with(&docs)) {
        let name = page
            .file_name()
            .expect("a page")
            .to_string_lossy()
            .into_owned();
        if name != "SUMMARY.md" && !listed.contains(&name) {
            wrong.push(format!("docs/{name} is not a chapter of docs/SUMMARY.md"));
        }
        let text = std::fs::read_to_string(page).expect("a page");
        for link in links(&text) {
            let path = link.split('#').next().unwrap_or_default();
            if path.starts_with("../") || path.starts_with('/') {
                wrong.push(format!(
                    "docs/{name}: {link} leads out of docs/, which mdBook does not serve: name a \
                     repository file as a path in code (`host/scenes/ball.toml`)"
                ));
            }
        }
    }
    for chapter in &listed {
        if !docs.join(chapter).is_file() {
            wrong.push(format!(
                "docs/SUMMARY.md lists {chapter}, which is not in docs/"
            ));
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

#[test]
fn anchors_are_named_as_github_names_them() {
    assert_eq!(
        anchor(" Narrow numbers: each quantity in the width it needs"),
        "narrow-numbers-each-quantity-in-the-width-it-needs"
    );
    assert_eq!(
        anchor(" `obscura firmware --profile`"),
        "obscura-firmware---profile"
    );
    assert_eq!(
        anchors("# A\n```\n# not a heading\n```\n## A\n"),
        BTreeSet::from(["a".to_owned(), "a-1".to_owned()])
    );
    assert_eq!(
        links(
            "[x](a.md#b), `[y](c.md)` and [z](https://example.org)\n<!-- book: echo '[w](d.md)' -->"
        ),
        ["a.md#b"]
    );
}
