//! What the harness writes, as a Unix tool writes it: standard output through [`say!`], which
//! hands back a failed write instead of panicking (a closed pipe ends the command quietly, a
//! full disk is an error), and output paths checked before any work is done, so that a
//! render of minutes does not end in "cannot write".

use anyhow::{Context, Result, bail};
use std::fmt;
use std::fs::{self, File, OpenOptions};
use std::io::{self, Write};
use std::path::Path;

/// Writes a line to standard output, like `println!`, and returns the `io::Result`.
macro_rules! say {
    ($($arg:tt)*) => {
        $crate::output::line(format_args!($($arg)*))
    };
}
pub(crate) use say;

/// Writes one line to standard output (see [`say!`]).
///
/// # Errors
/// When standard output is closed or full.
pub fn line(text: fmt::Arguments<'_>) -> io::Result<()> {
    let mut out = io::stdout().lock();
    out.write_fmt(text)
        .and_then(|()| out.write_all(b"\n"))
        .map_err(to_stdout)
}

/// Writes text to standard output as it is, without a line of its own (see [`say!`]).
///
/// # Errors
/// When standard output is closed or full.
pub fn text(text: fmt::Arguments<'_>) -> io::Result<()> {
    io::stdout().lock().write_fmt(text).map_err(to_stdout)
}

/// Flushes standard output (see [`say!`]).
///
/// # Errors
/// When standard output is closed or full.
pub fn flush() -> io::Result<()> {
    io::stdout().lock().flush().map_err(to_stdout)
}

/// Names standard output in a failed write, keeping its kind.
fn to_stdout(error: io::Error) -> io::Error {
    io::Error::new(
        error.kind(),
        format!("cannot write standard output: {error}"),
    )
}

/// Whether `error` is a write to a pipe whose reader has gone: the end of the command, not a
/// failure (`obscura scenes | head -1`).
pub fn is_closed_pipe(error: &anyhow::Error) -> bool {
    error
        .chain()
        .filter_map(|cause| cause.downcast_ref::<io::Error>())
        .any(|io| io.kind() == io::ErrorKind::BrokenPipe)
}

/// Fails, saying why, unless `path` can be written as a file: it is not a directory, its
/// directory exists or can be made (as `out/` is; made, it stays), and a file can be created
/// (or, where it exists, opened for writing) there. The file this creates, it removes.
///
/// # Errors
/// Why `path` cannot be written.
pub fn check_file(path: &Path) -> Result<()> {
    if path.is_dir() {
        bail!("cannot write {}: it is a directory", path.display());
    }
    if let Some(dir) = path.parent().filter(|dir| !dir.as_os_str().is_empty()) {
        fs::create_dir_all(dir).with_context(|| format!("cannot write {}", path.display()))?;
    }
    let existed = path.exists();
    OpenOptions::new()
        .write(true)
        .create(true)
        .truncate(false)
        .open(path)
        .with_context(|| format!("cannot write {}", path.display()))?;
    // Another process checking the same path (two commands writing `out.png` side by side)
    // may have removed it first: gone is what this wants.
    if !existed {
        match fs::remove_file(path) {
            Err(error) if error.kind() != io::ErrorKind::NotFound => {
                return Err(error).with_context(|| format!("cannot write {}", path.display()));
            }
            _ => {}
        }
    }
    Ok(())
}

/// Fails, saying why, unless `path` names an image format the harness writes (by its
/// extension) and can be written as a file ([`check_file`]).
///
/// # Errors
/// Why `path` cannot be written as an image.
pub fn check_image(path: &Path) -> Result<()> {
    if path.is_dir() {
        bail!("cannot write {}: it is a directory", path.display());
    }
    let format = image::ImageFormat::from_path(path).map_err(|_| {
        anyhow::anyhow!(
            "cannot write {}: name it .png (or .bmp, .tga, .ppm) so its format is known",
            path.display()
        )
    })?;
    if !format.writing_enabled() {
        bail!(
            "cannot write {}: this build writes .png, .bmp, .tga and .ppm images",
            path.display()
        );
    }
    check_file(path)
}

/// Creates `dir` (and its parents) and fails, saying why, unless files can be written in it.
///
/// # Errors
/// Why `dir` cannot be written.
pub fn check_dir(dir: &Path) -> Result<()> {
    fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let probe = dir.join(".obscura-can-write");
    File::create(&probe).with_context(|| format!("cannot write in {}", dir.display()))?;
    fs::remove_file(&probe).with_context(|| format!("cannot write in {}", dir.display()))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("obscura-output-{name}"));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn a_writable_file_passes_and_leaves_nothing_behind() {
        let dir = scratch("file");
        let path = dir.join("out.png");
        check_file(&path).unwrap();
        assert!(!path.exists());
        fs::write(&path, b"kept").unwrap();
        check_file(&path).unwrap();
        assert_eq!(fs::read(&path).unwrap(), b"kept");
    }

    #[test]
    fn a_missing_directory_is_made_and_a_file_in_a_file_or_a_directory_as_a_file_refused() {
        let dir = scratch("refused");
        check_file(&dir.join("made/for/out.png")).unwrap();
        assert!(dir.join("made/for").is_dir() && !dir.join("made/for/out.png").exists());
        fs::write(dir.join("a-file"), b"").unwrap();
        let under_a_file = check_file(&dir.join("a-file/out.png")).unwrap_err();
        assert!(
            format!("{under_a_file:#}").contains("cannot write"),
            "{under_a_file:#}"
        );
        let directory = check_file(&dir).unwrap_err();
        assert!(
            format!("{directory:#}").contains("is a directory"),
            "{directory:#}"
        );
        check_dir(&dir.join("made/here")).unwrap();
        let unknown = check_image(&dir.join("out.xyz")).unwrap_err();
        assert!(format!("{unknown:#}").contains(".png"), "{unknown:#}");
        check_image(&dir.join("out.png")).unwrap();
        assert!(dir.join("made/here").is_dir());
    }
}
