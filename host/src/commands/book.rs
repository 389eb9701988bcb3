//! `obscura book`: runs the command of every generated block of the README and the book
//! ([`crate::book`]) and writes what it prints into the block, or with `--check` says which
//! blocks print something other than the page holds. Pictures a command writes under
//! `docs/images/` are figures too: the check compares them byte for byte and puts the page's
//! back.

use crate::book::{Block, Page, first_difference};
use crate::cli::BookArgs;
use crate::output::say;
use crate::timing::TIMES_OMITTED;
use anyhow::{Context, Result, bail};
use std::collections::BTreeMap;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Instant, SystemTime};

/// Where the pictures a block may write are.
const PICTURES: &str = "docs/images";

/// Runs `obscura book`.
pub fn run(args: &BookArgs) -> Result<()> {
    let root = Path::new(".");
    if !root.join("docs/SUMMARY.md").is_file() {
        bail!(
            "no docs/SUMMARY.md here: run obscura book from the root of obscura's repository \
             (where README.md and docs/ are)"
        );
    }
    let pages = pages(root)?;
    let chosen = |file: &str, block: &Block| {
        (!args.quick || !block.kinds.slow)
            && args
                .only
                .as_deref()
                .is_none_or(|only| file.contains(only) || block.command.contains(only))
    };
    let total = pages
        .iter()
        .flat_map(|(file, page)| page.blocks().map(move |block| (file, block)))
        .filter(|(file, block)| chosen(file, block))
        .count();
    let mut pictures = Pictures::take(&root.join(PICTURES))?;
    let mut differing = Vec::new();
    let (mut run, mut timed, mut rewritten) = (0, 0, 0);
    let start = Instant::now();
    for (file, page) in &pages {
        let mut bodies = Vec::new();
        for block in page.blocks() {
            if !chosen(file, block) {
                bodies.push(page.body(block).to_owned());
                continue;
            }
            run += 1;
            let place = format!("{file}:{}", block.line);
            eprintln!("[{run}/{total}] {place}: {}", block.command);
            let printed = block.body_for(&execute(block, root).with_context(|| place.clone())?);
            let changed = pictures.changed()?;
            if args.check && block.kinds.timed {
                timed += 1;
                pictures.restore(&changed)?;
            } else if args.check {
                if printed != page.body(block) {
                    differing.push(format!(
                        "{place}: `{}` prints something else; {}",
                        block.command,
                        first_difference(page.body(block), &printed)
                    ));
                }
                for picture in &changed {
                    differing.push(format!(
                        "{place}: `{}` writes {} other than the repository's",
                        block.command,
                        picture.strip_prefix(root).unwrap_or(picture).display()
                    ));
                }
                pictures.restore(&changed)?;
            } else {
                pictures.keep(&changed)?;
            }
            bodies.push(printed);
        }
        let text = page.with_bodies(&bodies);
        if !args.check && text != page.text {
            // A page edited while its commands ran keeps the edit: it is written again by the
            // next run, not overwritten by this one's copy.
            let now = fs::read_to_string(root.join(file))
                .with_context(|| format!("cannot read {file}"))?;
            if now != page.text {
                bail!("{file} changed while its blocks ran; run obscura book again");
            }
            fs::write(root.join(file), &text).with_context(|| format!("cannot write {file}"))?;
            rewritten += 1;
        }
    }
    let seconds = start.elapsed().as_secs_f64();
    if args.check {
        for difference in &differing {
            say!("{difference}")?;
        }
        let unchecked = if timed > 0 {
            format!(" ({timed} of them timed: run, not compared)")
        } else {
            String::new()
        };
        eprintln!("checked {run} blocks{unchecked} in {seconds:.0} s");
        if !differing.is_empty() {
            bail!(
                "{} of the book's figures differ from what their commands print (above); \
                 `obscura book` writes them again",
                differing.len()
            );
        }
        say!("every figure of the {run} blocks is what its command prints")?;
    } else {
        say!("ran {run} blocks; rewrote {rewritten} pages")?;
        eprintln!("in {seconds:.0} s");
    }
    Ok(())
}

/// The README and every chapter of the book, by path from the root, with their blocks.
fn pages(root: &Path) -> Result<Vec<(String, Page)>> {
    let mut files = vec!["README.md".to_owned()];
    let mut chapters: Vec<String> = fs::read_dir(root.join("docs"))
        .context("cannot read docs/")?
        .map(|entry| Ok(entry?.file_name().to_string_lossy().into_owned()))
        .collect::<Result<_>>()?;
    chapters.retain(|name| name.ends_with(".md"));
    chapters.sort();
    files.extend(chapters.into_iter().map(|name| format!("docs/{name}")));
    files
        .into_iter()
        .map(|file| {
            let text = fs::read_to_string(root.join(&file))
                .with_context(|| format!("cannot read {file}"))?;
            let page = Page::parse(&file, &text)?;
            Ok((file, page))
        })
        .collect()
}

/// Runs a block's command in bash from the root, with this `obscura` first on the `PATH` and
/// times left out, and returns its standard output with the root's absolute path taken out of
/// it (so that a figure reads the same in any checkout).
fn execute(block: &Block, root: &Path) -> Result<String> {
    let obscura = std::env::current_exe().context("cannot find the running obscura")?;
    let mut path = vec![obscura.parent().map(Path::to_path_buf).unwrap_or_default()];
    path.extend(std::env::split_paths(
        &std::env::var_os("PATH").unwrap_or_default(),
    ));
    let output = Command::new("bash")
        .arg("-c")
        .arg(&block.command)
        .current_dir(root)
        .env("PATH", std::env::join_paths(path)?)
        .env(TIMES_OMITTED.0, TIMES_OMITTED.1)
        .stdin(Stdio::null())
        .output()
        .context("cannot run bash")?;
    let stdout = String::from_utf8_lossy(&output.stdout);
    let stderr = String::from_utf8_lossy(&output.stderr);
    if output.status.success() == block.kinds.fails {
        let tail: Vec<&str> = stderr.lines().rev().take(20).collect();
        let tail: Vec<&str> = tail.into_iter().rev().collect();
        bail!(
            "`{}` {} ({}); its standard error ends:\n{}",
            block.command,
            if block.kinds.fails {
                "succeeded where its marker says it fails (drop `fails`, or fix the command)"
            } else {
                "failed"
            },
            output.status,
            tail.join("\n")
        );
    }
    let absolute = fs::canonicalize(root)?;
    Ok(stdout.replace(&format!("{}/", absolute.display()), ""))
}

/// The pictures under `docs/images/` as they were before a block ran: each file's bytes and
/// when it was last written.
struct Pictures {
    dir: PathBuf,
    files: BTreeMap<PathBuf, (SystemTime, Vec<u8>)>,
}

impl Pictures {
    fn take(dir: &Path) -> Result<Self> {
        let mut files = BTreeMap::new();
        for path in walk(dir)? {
            files.insert(path.clone(), read(&path)?);
        }
        Ok(Self {
            dir: dir.to_owned(),
            files,
        })
    }

    /// The files written since, whose bytes differ, and the files that are new.
    fn changed(&self) -> Result<Vec<PathBuf>> {
        let mut changed = Vec::new();
        for path in walk(&self.dir)? {
            let modified = fs::metadata(&path)?.modified()?;
            match self.files.get(&path) {
                Some((before, _)) if *before == modified => {}
                Some((_, bytes)) if *bytes == fs::read(&path)? => {}
                _ => changed.push(path),
            }
        }
        Ok(changed)
    }

    /// Puts each of `changed` back as it was (removing a new one).
    fn restore(&mut self, changed: &[PathBuf]) -> Result<()> {
        for path in changed {
            match self.files.get(path) {
                Some((_, bytes)) => fs::write(path, bytes)?,
                None => fs::remove_file(path)?,
            }
        }
        self.keep(changed)
    }

    /// Takes each of `changed` as it is now.
    fn keep(&mut self, changed: &[PathBuf]) -> Result<()> {
        for path in changed {
            if path.exists() {
                self.files.insert(path.clone(), read(path)?);
            }
        }
        Ok(())
    }
}

/// A file's last write and bytes.
fn read(path: &Path) -> Result<(SystemTime, Vec<u8>)> {
    let bytes = fs::read(path).with_context(|| format!("cannot read {}", path.display()))?;
    Ok((fs::metadata(path)?.modified()?, bytes))
}

/// Every file under `dir`, depth first.
fn walk(dir: &Path) -> Result<Vec<PathBuf>> {
    let mut files = Vec::new();
    if !dir.is_dir() {
        return Ok(files);
    }
    for entry in fs::read_dir(dir).with_context(|| format!("cannot read {}", dir.display()))? {
        let path = entry?.path();
        if path.is_dir() {
            files.extend(walk(&path)?);
        } else {
            files.push(path);
        }
    }
    Ok(files)
}
