//! Positioned diagnostics of text inputs (wrinkle description files): file, line, column,
//! what was expected and what was found. Its own module so that [`crate::base::error`] and
//! [`crate::layers::wrinkles::wrinkle_file`] both depend on it instead of on each other.

use std::fmt;
use std::path::PathBuf;

/// One problem in a wrinkle file, with its 1-based position.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Diagnostic {
    pub file: PathBuf,
    /// 1-based line number.
    pub line: usize,
    /// 1-based column, in characters.
    pub column: usize,
    pub kind: DiagnosticKind,
    /// What a valid input looks like here.
    pub expected: String,
    /// What the file has instead (empty for a missing item).
    pub found: String,
}

/// The kinds of wrinkle-file errors (docs/models.md §3).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DiagnosticKind {
    /// A `key=value` line before the first `!`.
    KeyBeforeGroup,
    /// The same key twice in one group.
    RepeatedKey,
    /// A key that is not part of the format.
    UnknownKey,
    /// A line that is neither `!`, `key=value`, a comment nor blank.
    Syntax,
    /// A number (or point, or name) that cannot be read.
    MalformedValue,
    /// A well-formed value outside its range.
    OutOfRange,
    /// A group without one of `ma`, `mb`, `n`.
    MissingKey,
    /// `ma` and `mb` are the same point.
    IdenticalEnds,
    /// The file is not UTF-8 text.
    NotUtf8,
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let what = match self.kind {
            DiagnosticKind::KeyBeforeGroup => "key before the first `!`",
            DiagnosticKind::RepeatedKey => "repeated key",
            DiagnosticKind::UnknownKey => "unknown key",
            DiagnosticKind::Syntax => "syntax error",
            DiagnosticKind::MalformedValue => "malformed value",
            DiagnosticKind::OutOfRange => "value out of range",
            DiagnosticKind::MissingKey => "missing key",
            DiagnosticKind::IdenticalEnds => "ma and mb are the same point",
            DiagnosticKind::NotUtf8 => "not UTF-8 text",
        };
        write!(
            f,
            "{}:{}:{}: {what}: expected {}",
            self.file.display(),
            self.line,
            self.column,
            self.expected
        )?;
        if self.found.is_empty() {
            Ok(())
        } else {
            write!(f, ", found `{}`", shorten(&self.found, 80))
        }
    }
}

/// All the errors of one or more wrinkle files, in file and line order.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ParseErrors(pub Vec<Diagnostic>);

impl fmt::Display for ParseErrors {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, d) in self.0.iter().enumerate() {
            if i > 0 {
                writeln!(f)?;
            }
            write!(f, "{d}")?;
        }
        Ok(())
    }
}

impl std::error::Error for ParseErrors {}
/// `text` cut to at most `max_chars` characters, with `…` where it was cut, so that a
/// 10 MB token in an input does not become 10 MB of error message.
pub fn shorten(text: &str, max_chars: usize) -> String {
    match text.char_indices().nth(max_chars) {
        None => text.to_owned(),
        Some((cut, _)) => format!("{}…", &text[..cut]),
    }
}
