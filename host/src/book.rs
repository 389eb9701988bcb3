//! The generated blocks of the README and the book: where each is, what command prints it, and
//! the page with a block's body replaced (`obscura book` runs the commands).
//!
//! A block is a marker line naming its command, the body the command printed, and an end line:
//!
//! ````text
//! <!-- book: obscura compare whitted --format i16f16 --size 240x240 -->
//! ```text
//! $ obscura compare whitted --format i16f16 --size 240x240
//! …what it printed…
//! ```
//! <!-- /book -->
//! ````
//!
//! Words between `book` and the colon say more about the command ([`Kinds`]): `markdown` (it
//! prints Markdown, set under the command as it is), `slow` (it takes more than seconds; the
//! quick check leaves it out), `fails` (it must exit non-zero: a refusal), `timed` (it prints
//! wall-clock times: written, never compared). The markers are HTML comments, which GitHub and
//! mdBook leave unseen.

use anyhow::{Result, bail};

/// What ends a block.
pub const END: &str = "<!-- /book -->";
/// What starts a block's marker.
const START: &str = "<!-- book";

/// What the words of a marker say about its command.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Kinds {
    /// Its output is Markdown, set under the command as it is (not in a code block).
    pub markdown: bool,
    /// It takes more than a few seconds: `obscura book --quick` leaves it out.
    pub slow: bool,
    /// It must exit non-zero.
    pub fails: bool,
    /// Its output holds wall-clock times: written by `obscura book`, never compared.
    pub timed: bool,
}

impl Kinds {
    /// The words a marker may hold.
    pub const WORDS: [&str; 4] = ["markdown", "slow", "fails", "timed"];

    fn set(&mut self, word: &str) -> bool {
        let flag = match word {
            "markdown" => &mut self.markdown,
            "slow" => &mut self.slow,
            "fails" => &mut self.fails,
            "timed" => &mut self.timed,
            _ => return false,
        };
        *flag = true;
        true
    }
}

/// One generated block of a page.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Block {
    /// The marker's line, from 1.
    pub line: usize,
    /// The shell command that prints the body.
    pub command: String,
    /// What the marker's words say about it.
    pub kinds: Kinds,
    /// Where its body is in its page's text (bytes): every line with its newline.
    span: std::ops::Range<usize>,
}

impl Block {
    /// The body for what the command printed: under `$ command` in a text block, or with
    /// `markdown` the command in a shell block and the output beneath as it is. Each line's
    /// trailing blanks go, and the output ends with exactly one newline.
    #[must_use]
    pub fn body_for(&self, output: &str) -> String {
        let mut printed = String::new();
        for line in output.trim_end().lines() {
            printed.push_str(line.trim_end());
            printed.push('\n');
        }
        let command = &self.command;
        if self.kinds.markdown {
            format!("```sh\n{command}\n```\n\n{printed}")
        } else {
            format!("```text\n$ {command}\n{printed}```\n")
        }
    }
}

/// A page: its text and the blocks in it.
#[derive(Debug)]
pub struct Page {
    /// The page as it is.
    pub text: String,
    /// Its blocks, in order.
    blocks: Vec<Block>,
}

impl Page {
    /// Finds the blocks of `text`; `name` is the page's path, for errors (`name:line:column:
    /// what is wrong`).
    ///
    /// # Errors
    /// A marker that does not parse, a marker inside a block, or a block without its end.
    pub fn parse(name: &str, text: &str) -> Result<Self> {
        let mut blocks = Vec::new();
        let mut open: Option<(Block, usize)> = None;
        let mut offset = 0;
        for (index, line) in text.split_inclusive('\n').enumerate() {
            let number = index + 1;
            let trimmed = line.trim();
            let next = offset + line.len();
            if trimmed == END {
                let Some((block, start)) = open.take() else {
                    bail!("{name}:{number}:1: {END} without a block to end; remove it");
                };
                blocks.push(Block {
                    span: start..offset,
                    ..block
                });
            } else if trimmed.starts_with(START) {
                if let Some((block, _)) = &open {
                    bail!(
                        "{name}:{number}:1: a book marker inside the block of line {}; end that \
                         block with {END} first",
                        block.line
                    );
                }
                open = Some((marker(name, number, line)?, next));
            }
            offset = next;
        }
        if let Some((block, _)) = open {
            bail!(
                "{name}:{}:1: the block of `{}` has no end; add a line {END} after its body",
                block.line,
                block.command
            );
        }
        Ok(Self {
            text: text.to_owned(),
            blocks,
        })
    }

    /// The page's blocks, in order.
    pub fn blocks(&self) -> impl Iterator<Item = &Block> {
        self.blocks.iter()
    }

    /// The body of `block`, one of its blocks, as the page holds it.
    #[must_use]
    pub fn body(&self, block: &Block) -> &str {
        self.text.get(block.span.clone()).unwrap_or_default()
    }

    /// The page with each block's body replaced by `bodies`' (in order, one a block).
    #[must_use]
    pub fn with_bodies(&self, bodies: &[String]) -> String {
        assert_eq!(bodies.len(), self.blocks.len(), "one body a block");
        let mut text = String::with_capacity(self.text.len());
        let mut from = 0;
        for (block, body) in self.blocks.iter().zip(bodies) {
            text.push_str(&self.text[from..block.span.start]);
            text.push_str(body);
            from = block.span.end;
        }
        text.push_str(&self.text[from..]);
        text
    }
}

/// The block a marker line starts: `<!-- book WORDS: COMMAND -->`.
fn marker(name: &str, number: usize, line: &str) -> Result<Block> {
    let indent = line.len() - line.trim_start().len();
    let at = |column: usize| format!("{name}:{number}:{}", indent + column + 1);
    let marker = line.trim();
    let Some(inner) = marker.strip_suffix("-->") else {
        bail!(
            "{}: a book marker ends on its own line with -->; write it as <!-- book: COMMAND -->",
            at(marker.len())
        );
    };
    let rest = &inner[START.len()..];
    let Some((words, command)) = rest.split_once(':') else {
        bail!(
            "{}: a book marker names its command after a colon: <!-- book: COMMAND -->",
            at(START.len())
        );
    };
    let mut kinds = Kinds::default();
    let mut offset = 0;
    for word in words.split(' ') {
        if !word.is_empty() && !kinds.set(word) {
            bail!(
                "{}: `{word}` is not a word a book marker takes; it takes {}",
                at(START.len() + offset),
                Kinds::WORDS.join(", ")
            );
        }
        offset += word.len() + 1;
    }
    let command = command.trim();
    if command.is_empty() {
        bail!(
            "{}: the book marker names no command; write it after the colon",
            at(START.len() + words.len() + 1)
        );
    }
    Ok(Block {
        line: number,
        command: command.to_owned(),
        kinds,
        span: 0..0,
    })
}

/// The first line where `expected` and `found` differ, for a report: its number in the body
/// (from 1) and both lines (a missing line is empty).
#[must_use]
pub fn first_difference(expected: &str, found: &str) -> String {
    let mut expected_lines = expected.lines();
    let mut found_lines = found.lines();
    let mut number = 1;
    loop {
        match (expected_lines.next(), found_lines.next()) {
            (None, None) => return "the same lines, other line ends".to_owned(),
            (a, b) if a == b => number += 1,
            (a, b) => {
                return format!(
                    "line {number} of the block\n  the page: {}\n  printed:  {}",
                    a.unwrap_or("(nothing)"),
                    b.unwrap_or("(nothing)")
                );
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const PAGE: &str = "# A page\n\nProse.\n\n<!-- book slow: obscura scenes -->\nold\n<!-- /book -->\n\n  <!-- book markdown: obscura settings -->\n<!-- /book -->\nEnd.\n";

    #[test]
    fn finds_each_block_with_its_command_words_and_body() {
        let page = Page::parse("p.md", PAGE).unwrap();
        let blocks: Vec<_> = page.blocks().collect();
        assert_eq!(blocks.len(), 2);
        assert_eq!(blocks[0].line, 5);
        assert_eq!(blocks[0].command, "obscura scenes");
        assert_eq!(
            blocks[0].kinds,
            Kinds {
                slow: true,
                ..Kinds::default()
            }
        );
        assert_eq!(page.body(blocks[0]), "old\n");
        assert!(blocks[1].kinds.markdown);
        assert_eq!(page.body(blocks[1]), "");
    }

    #[test]
    fn replaces_the_bodies_and_nothing_else() {
        let page = Page::parse("p.md", PAGE).unwrap();
        let text = page.with_bodies(&["new\n".to_owned(), "table\n".to_owned()]);
        assert_eq!(
            text,
            PAGE.replace("old\n", "new\n").replace(
                "settings -->\n<!-- /book -->",
                "settings -->\ntable\n<!-- /book -->"
            )
        );
        let rewritten = Page::parse("p.md", &text).unwrap();
        assert!(rewritten.blocks().all(|b| !rewritten.body(b).is_empty()));
    }

    #[test]
    fn writes_text_under_its_command_and_markdown_as_it_is() {
        let page = Page::parse("p.md", PAGE).unwrap();
        let blocks: Vec<_> = page.blocks().collect();
        assert_eq!(
            blocks[0].body_for("a  \nb\n\n\n"),
            "```text\n$ obscura scenes\na\nb\n```\n"
        );
        assert_eq!(
            blocks[1].body_for("| a |\n"),
            "```sh\nobscura settings\n```\n\n| a |\n"
        );
    }

    #[test]
    fn says_where_a_marker_is_wrong_and_how_to_fix_it() {
        let error = |text: &str| Page::parse("p.md", text).unwrap_err().to_string();
        assert_eq!(
            error("x\n<!-- book quick: obscura scenes -->\n<!-- /book -->\n"),
            "p.md:2:11: `quick` is not a word a book marker takes; it takes markdown, slow, \
             fails, timed"
        );
        assert!(error("<!-- book obscura scenes -->\n").starts_with("p.md:1:10: "));
        assert!(error("<!-- book: -->\n<!-- /book -->\n").starts_with("p.md:1:11: "));
        assert!(error("<!-- book: a\n").starts_with("p.md:1:"));
        assert!(error("<!-- book: a -->\n").contains("has no end"));
        assert!(error("<!-- book: a -->\n<!-- book: b -->\n").starts_with("p.md:2:1: "));
        assert!(error("<!-- /book -->\n").starts_with("p.md:1:1: "));
    }

    #[test]
    fn names_the_first_differing_line() {
        assert_eq!(
            first_difference("a\nb\nc\n", "a\nB\nc\n"),
            "line 2 of the block\n  the page: b\n  printed:  B"
        );
        assert!(first_difference("a\n", "a\nb\n").ends_with("printed:  b"));
    }
}
