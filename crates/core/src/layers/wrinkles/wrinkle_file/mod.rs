//! The wrinkle description file (docs/models.md §3, [T] App. A.3): parser, diagnostics and writer.
//!
//! ```text
//! # comment to end of line
//! !                       # starts a new wrinkle group (a fibre)
//! ma=0.423;0.727          # key=value; a point is "u;v"
//! mb=0.439;0.640
//! n=3
//! ```
//!
//! Keys are case-insensitive; spaces are allowed around every token; CRLF line ends are
//! accepted. `ma`, `mb` and `n` are required, the others take docs/models.md §2's defaults.
//! agesim extensions (optional, so [T]'s files load unchanged):
//! - `profile` — `abs_sin` (default), `sin`, `gauss`, `parabola`, `crease` or `fold`
//!   (docs/models.md §2 profiles);
//! - `depth` — the fibre's relative amplitude A in [0, 100], default 1;
//! - `irregularity` — in [0, 1], default 0: each wrinkle's depth varies along it and between
//!   the wrinkles of the group by up to this fraction; `waviness` — in [0, 0.5] periods of
//!   the spacing, default 0: each wrinkle line wanders across; `seed` — an integer, default
//!   the group's number in the file (docs/models.md §2 "Irregularity");
//! - `space` — `uv` (default) or `surface`: the group's lines are straight in the UV
//!   layout, or on the head's surface where the layout bends (docs/models.md §3);
//! - `ageOnset`, `ageFull` — the fibre's age curve (`docs/models.md` "Age"): the age in
//!   years at which its wrinkles start to show and at which they reach full depth, both in
//!   [0, 150], given together, `ageFull ≥ ageOnset`; `ageShape` — `smoothstep` (default)
//!   or `linear`. A group without them follows the project's `age.large` curve.
//!
//! Every error is collected (not only the first), each with file, line, column, what was
//! expected and what was found; a file with any error loads nothing.

use std::path::Path;

use crate::age::{AgeCurve, CurveShape};
use crate::base::error::Error;
use crate::layers::wrinkles::fibre_params;
use crate::layers::wrinkles::muscle::{
    self, DEFAULT_DEPTH, DEFAULT_MAX_ANGLE, DEFAULT_OMEGA_LOW, DEFAULT_REL_WIDTH, Fibre, Profile,
    Space,
};

/// One wrinkle group: a fibre and the comment lines written just before its `!`.
#[derive(Clone, Debug, PartialEq)]
pub struct WrinkleGroup {
    pub fibre: Fibre,
    /// The group's own age curve (`ageOnset`/`ageFull`/`ageShape`), or `None` for the
    /// layer's default.
    pub age: Option<AgeCurve>,
    /// Comment lines (without the leading `#`) that preceded the group's `!` line.
    pub comments: Vec<String>,
}

/// A parsed wrinkle description file.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct WrinkleFile {
    pub groups: Vec<WrinkleGroup>,
    /// Comment lines after the last group's keys that precede no further group.
    pub trailing_comments: Vec<String>,
}

impl WrinkleFile {
    /// The fibres, in file order.
    pub fn fibres(&self) -> impl Iterator<Item = &Fibre> {
        self.groups.iter().map(|g| &g.fibre)
    }
}

pub use crate::base::diagnostic::{Diagnostic, DiagnosticKind, ParseErrors};

/// The keys of the format, in the order the writer uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Key {
    Ma,
    Mb,
    N,
    RelWidth,
    MaxAngle,
    OmegaLow,
    Profile,
    Depth,
    Irregularity,
    Waviness,
    Seed,
    Space,
    AgeOnset,
    AgeFull,
    AgeShape,
}

impl Key {
    const ALL: [Key; 15] = [
        Key::Ma,
        Key::Mb,
        Key::N,
        Key::RelWidth,
        Key::MaxAngle,
        Key::OmegaLow,
        Key::Profile,
        Key::Depth,
        Key::Irregularity,
        Key::Waviness,
        Key::Seed,
        Key::Space,
        Key::AgeOnset,
        Key::AgeFull,
        Key::AgeShape,
    ];

    fn name(self) -> &'static str {
        match self {
            Key::Ma => "ma",
            Key::Mb => "mb",
            Key::N => "n",
            Key::RelWidth => "relWidth",
            Key::MaxAngle => "maxAngle",
            Key::OmegaLow => "omegaLow",
            Key::Profile => "profile",
            Key::Depth => "depth",
            Key::Irregularity => "irregularity",
            Key::Waviness => "waviness",
            Key::Seed => "seed",
            Key::Space => "space",
            Key::AgeOnset => "ageOnset",
            Key::AgeFull => "ageFull",
            Key::AgeShape => "ageShape",
        }
    }

    fn from_name(s: &str) -> Option<Key> {
        Self::ALL
            .into_iter()
            .find(|k| k.name().eq_ignore_ascii_case(s))
    }
}

/// A range check of `muscle` for one numeric key.
type RangeCheck = fn(f32) -> Result<f32, muscle::RangeError>;

/// Values of one group while it is being read.
#[derive(Default)]
struct PendingGroup {
    /// Line and column of the `!`.
    line: usize,
    column: usize,
    comments: Vec<String>,
    ma: Option<([f32; 2], usize, usize)>,
    mb: Option<([f32; 2], usize, usize)>,
    n: Option<u32>,
    rel_width: Option<f32>,
    max_angle: Option<f32>,
    omega_low: Option<f32>,
    profile: Option<Profile>,
    depth: Option<f32>,
    irregularity: Option<f32>,
    waviness: Option<f32>,
    seed: Option<u32>,
    space: Option<Space>,
    /// The group's number in the file, from 1: its seed unless `seed` says otherwise.
    number: u32,
    age_onset: Option<f32>,
    age_full: Option<f32>,
    age_shape: Option<CurveShape>,
    /// Keys seen, to report repeats even when the first value was malformed.
    seen: Vec<Key>,
    /// Any error inside this group (then it is not built).
    broken: bool,
}

/// Reads a value named by one of `all` (`name`, case-insensitive) into `slot`, or reports
/// "one of …" through `bad`. Whether it was read.
fn read_named<T: Copy>(
    all: &[T],
    name: fn(T) -> &'static str,
    text: &str,
    slot: &mut Option<T>,
    bad: &mut dyn FnMut(DiagnosticKind, &str),
) -> bool {
    match all
        .iter()
        .copied()
        .find(|&x| name(x).eq_ignore_ascii_case(text))
    {
        Some(x) => {
            *slot = Some(x);
            true
        }
        None => {
            let names: Vec<&str> = all.iter().map(|&x| name(x)).collect();
            bad(
                DiagnosticKind::MalformedValue,
                &format!("one of {}", names.join(", ")),
            );
            false
        }
    }
}

/// Reads and parses a wrinkle file from disk.
pub fn load(path: &Path) -> Result<WrinkleFile, Error> {
    let bytes = crate::base::limits::read_file(path, crate::base::limits::MAX_TEXT_FILE_BYTES)?;
    Ok(parse_bytes(&bytes, path)?)
}

/// Parses raw bytes; non-UTF-8 input is an error at the first invalid byte.
pub fn parse_bytes(bytes: &[u8], file: &Path) -> Result<WrinkleFile, ParseErrors> {
    match std::str::from_utf8(bytes) {
        Ok(text) => parse(text, file),
        Err(e) => {
            let valid = &bytes[..e.valid_up_to()];
            let line = valid.iter().filter(|&&b| b == b'\n').count() + 1;
            let line_start = valid.iter().rposition(|&b| b == b'\n').map_or(0, |p| p + 1);
            let column = String::from_utf8_lossy(&valid[line_start..])
                .chars()
                .count()
                + 1;
            Err(ParseErrors(vec![Diagnostic {
                file: file.to_owned(),
                line,
                column,
                kind: DiagnosticKind::NotUtf8,
                expected: "UTF-8 text".into(),
                found: format!("byte 0x{:02x}", bytes[e.valid_up_to()]),
            }]))
        }
    }
}

/// Parses the text of a wrinkle file. `file` is only used in diagnostics.
pub fn parse(text: &str, file: &Path) -> Result<WrinkleFile, ParseErrors> {
    let mut errors = Vec::new();
    let mut groups = Vec::new();
    let mut current: Option<PendingGroup> = None;
    let mut group_count = 0u32;
    let mut comments: Vec<String> = Vec::new();
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);

    for (index, raw_line) in text.split('\n').enumerate() {
        let line_no = index + 1;
        let raw_line = raw_line.strip_suffix('\r').unwrap_or(raw_line);
        let (content, comment) = match raw_line.find('#') {
            Some(p) => (&raw_line[..p], Some(&raw_line[p + 1..])),
            None => (raw_line, None),
        };
        let column_of = |byte: usize| raw_line[..byte].chars().count() + 1;
        let trimmed = content.trim();
        let start = content.len() - content.trim_start().len();
        if trimmed.is_empty() {
            if let Some(c) = comment {
                comments.push(c.to_owned());
            }
            continue;
        }
        let mut error = |column: usize, kind, expected: &str, found: &str| {
            errors.push(Diagnostic {
                file: file.to_owned(),
                line: line_no,
                column,
                kind,
                expected: expected.to_owned(),
                found: found.to_owned(),
            });
        };

        if trimmed == "!" {
            if let Some(done) = current.take() {
                groups.extend(finish_group(done, file, &mut errors));
            }
            group_count += 1;
            current = Some(PendingGroup {
                line: line_no,
                column: column_of(start),
                comments: std::mem::take(&mut comments),
                number: group_count,
                ..PendingGroup::default()
            });
            continue;
        }
        // A trailing comment on a key line is not kept: only whole-line comments are.
        let Some(eq) = content.find('=') else {
            error(
                column_of(start),
                DiagnosticKind::Syntax,
                "`!`, `key=value`, a comment or a blank line",
                trimmed,
            );
            if let Some(g) = current.as_mut() {
                g.broken = true;
            }
            continue;
        };
        let key_text = content[..eq].trim();
        let value_raw = &content[eq + 1..];
        let value_text = value_raw.trim();
        let value_col = column_of(eq + 1 + (value_raw.len() - value_raw.trim_start().len()));
        let key_col = column_of(start);

        let Some(group) = current.as_mut() else {
            error(
                key_col,
                DiagnosticKind::KeyBeforeGroup,
                "`!` to start a wrinkle group first",
                key_text,
            );
            continue;
        };
        let Some(key) = Key::from_name(key_text) else {
            let known: Vec<&str> = Key::ALL.iter().map(|k| k.name()).collect();
            error(
                key_col,
                DiagnosticKind::UnknownKey,
                &format!("one of {}", known.join(", ")),
                key_text,
            );
            group.broken = true;
            continue;
        };
        if group.seen.contains(&key) {
            error(
                key_col,
                DiagnosticKind::RepeatedKey,
                &format!("`{}` at most once per group", key.name()),
                key_text,
            );
            group.broken = true;
            continue;
        }
        group.seen.push(key);

        let mut bad = |kind, expected: &str| {
            error(value_col, kind, expected, value_text);
        };
        let ok = match key {
            Key::Ma | Key::Mb => match parse_point(value_text) {
                None => {
                    bad(DiagnosticKind::MalformedValue, "a UV point `u;v`");
                    false
                }
                Some(p) => match muscle::check_point(p) {
                    Ok(p) => {
                        let slot = if key == Key::Ma {
                            &mut group.ma
                        } else {
                            &mut group.mb
                        };
                        *slot = Some((p, line_no, value_col));
                        true
                    }
                    Err(e) => {
                        bad(DiagnosticKind::OutOfRange, &e.expected);
                        false
                    }
                },
            },
            Key::N => match value_text.parse::<i64>() {
                Err(_) => {
                    bad(DiagnosticKind::MalformedValue, "an integer");
                    false
                }
                Ok(n) => match muscle::check_count(n) {
                    Ok(n) => {
                        group.n = Some(n);
                        true
                    }
                    Err(e) => {
                        bad(DiagnosticKind::OutOfRange, &e.expected);
                        false
                    }
                },
            },
            Key::Profile => read_named(
                &Profile::ALL,
                Profile::name,
                value_text,
                &mut group.profile,
                &mut bad,
            ),
            Key::Space => read_named(
                &Space::ALL,
                Space::name,
                value_text,
                &mut group.space,
                &mut bad,
            ),
            Key::Seed => match value_text.parse::<u32>() {
                Ok(seed) => {
                    group.seed = Some(seed);
                    true
                }
                Err(_) => {
                    bad(
                        DiagnosticKind::MalformedValue,
                        "an integer in 0..=4294967295",
                    );
                    false
                }
            },
            Key::AgeShape => read_named(
                &CurveShape::ALL,
                CurveShape::name,
                value_text,
                &mut group.age_shape,
                &mut bad,
            ),
            Key::RelWidth
            | Key::MaxAngle
            | Key::OmegaLow
            | Key::Depth
            | Key::Irregularity
            | Key::Waviness
            | Key::AgeOnset
            | Key::AgeFull => {
                let (check, slot): (RangeCheck, &mut Option<f32>) = match key {
                    Key::RelWidth => (|v| fibre_params::REL_WIDTH.check(v), &mut group.rel_width),
                    Key::MaxAngle => (|v| fibre_params::MAX_ANGLE.check(v), &mut group.max_angle),
                    Key::OmegaLow => (|v| fibre_params::OMEGA_LOW.check(v), &mut group.omega_low),
                    Key::AgeOnset => (check_years, &mut group.age_onset),
                    Key::AgeFull => (check_years, &mut group.age_full),
                    Key::Irregularity => (
                        |v| fibre_params::IRREGULARITY.check(v),
                        &mut group.irregularity,
                    ),
                    Key::Waviness => (|v| fibre_params::WAVINESS.check(v), &mut group.waviness),
                    _ => (|v| fibre_params::DEPTH.check(v), &mut group.depth),
                };
                match parse_number(value_text) {
                    None => {
                        bad(DiagnosticKind::MalformedValue, "a number");
                        false
                    }
                    Some(x) => match check(x) {
                        Ok(x) => {
                            *slot = Some(x);
                            true
                        }
                        Err(e) => {
                            bad(DiagnosticKind::OutOfRange, &e.expected);
                            false
                        }
                    },
                }
            }
        };
        if !ok {
            group.broken = true;
        }
    }
    if let Some(done) = current.take() {
        groups.extend(finish_group(done, file, &mut errors));
    }
    if errors.is_empty() {
        Ok(WrinkleFile {
            groups,
            trailing_comments: comments,
        })
    } else {
        errors.sort_by_key(|d| (d.line, d.column));
        Err(ParseErrors(errors))
    }
}

/// An age in years, [0, 150].
fn check_years(y: f32) -> Result<f32, muscle::RangeError> {
    let (lo, hi) = crate::age::YEARS_RANGE;
    if (lo..=hi).contains(&y) {
        Ok(y)
    } else {
        Err(muscle::RangeError {
            expected: format!("an age in years in [{lo}, {hi}]"),
        })
    }
}

/// A finite number; Rust's float syntax (which includes `1e-3`, not `inf`/`nan`).
fn parse_number(s: &str) -> Option<f32> {
    s.parse::<f32>().ok().filter(|x| x.is_finite())
}

/// `u;v`, spaces allowed around both numbers.
fn parse_point(s: &str) -> Option<[f32; 2]> {
    let (a, b) = s.split_once(';')?;
    Some([parse_number(a.trim())?, parse_number(b.trim())?])
}

fn finish_group(
    g: PendingGroup,
    file: &Path,
    errors: &mut Vec<Diagnostic>,
) -> Option<WrinkleGroup> {
    let mut missing = Vec::new();
    // A key that was present but malformed is already reported; only absent keys count.
    for (key, present) in [
        (Key::Ma, g.seen.contains(&Key::Ma)),
        (Key::Mb, g.seen.contains(&Key::Mb)),
        (Key::N, g.seen.contains(&Key::N)),
    ] {
        if !present {
            missing.push(key.name());
        }
    }
    if !missing.is_empty() {
        errors.push(Diagnostic {
            file: file.to_owned(),
            line: g.line,
            column: g.column,
            kind: DiagnosticKind::MissingKey,
            expected: format!("the group started here to have `{}`", missing.join("`, `")),
            found: String::new(),
        });
        return None;
    }
    if let (Some((a, _, _)), Some((b, line, column))) = (g.ma, g.mb)
        && a == b
    {
        errors.push(Diagnostic {
            file: file.to_owned(),
            line,
            column,
            kind: DiagnosticKind::IdenticalEnds,
            expected: "mb different from ma".into(),
            found: format!("{};{}", b[0], b[1]),
        });
        return None;
    }
    let age = match (g.age_onset, g.age_full) {
        (None, None) if g.age_shape.is_none() => None,
        (Some(onset), Some(full)) if full >= onset => {
            Some(AgeCurve::new(onset, full, g.age_shape.unwrap_or_default()))
        }
        (Some(onset), Some(full)) => {
            errors.push(Diagnostic {
                file: file.to_owned(),
                line: g.line,
                column: g.column,
                kind: DiagnosticKind::OutOfRange,
                expected: "ageFull ≥ ageOnset".into(),
                found: format!("ageOnset={onset}, ageFull={full}"),
            });
            return None;
        }
        _ => {
            if !g.broken {
                errors.push(Diagnostic {
                    file: file.to_owned(),
                    line: g.line,
                    column: g.column,
                    kind: DiagnosticKind::MissingKey,
                    expected:
                        "the group started here to have both `ageOnset` and `ageFull` (or neither)"
                            .into(),
                    found: String::new(),
                });
            }
            return None;
        }
    };
    if g.broken {
        return None;
    }
    let (ma, mb, n) = (g.ma?.0, g.mb?.0, g.n?);
    // Every value was range-checked above, so these constructors cannot fail; if they
    // ever did, the group is dropped and the error reported at its `!`.
    let built = Fibre::new(ma, mb, n)
        .and_then(|f| f.with_rel_width(g.rel_width.unwrap_or(DEFAULT_REL_WIDTH)))
        .and_then(|f| f.with_max_angle(g.max_angle.unwrap_or(DEFAULT_MAX_ANGLE)))
        .and_then(|f| f.with_omega_low(g.omega_low.unwrap_or(DEFAULT_OMEGA_LOW)))
        .and_then(|f| f.with_depth(g.depth.unwrap_or(DEFAULT_DEPTH)))
        .and_then(|f| f.with_irregularity(g.irregularity.unwrap_or(0.0)))
        .and_then(|f| f.with_waviness(g.waviness.unwrap_or(0.0)))
        .map(|f| {
            f.with_profile(g.profile.unwrap_or_default())
                .with_seed(g.seed.unwrap_or(g.number))
                .with_space(g.space.unwrap_or_default())
        });
    match built {
        Ok(fibre) => Some(WrinkleGroup {
            fibre,
            age,
            comments: g.comments,
        }),
        Err(e) => {
            errors.push(Diagnostic {
                file: file.to_owned(),
                line: g.line,
                column: g.column,
                kind: DiagnosticKind::OutOfRange,
                expected: "a valid wrinkle group".into(),
                found: e.to_string(),
            });
            None
        }
    }
}

/// Writes a wrinkle file: each group's comments, `!`, then its keys in a fixed order
/// (`ma`, `mb`, `n`, `relWidth`, `maxAngle`, `omegaLow`, and the extension keys `profile`
/// `depth` only when they differ from their defaults and `ageOnset`/`ageFull`/`ageShape` when the group has its own curve, so [T]'s reader can still load
/// files without extensions). Numbers use the shortest text that reads back exactly.
pub fn write(file: &WrinkleFile) -> String {
    use std::fmt::Write as _;
    let mut out = String::new();
    for (i, g) in file.groups.iter().enumerate() {
        if i > 0 {
            out.push('\n');
        }
        for c in &g.comments {
            let _ = writeln!(out, "#{c}");
        }
        let f = &g.fibre;
        let _ = writeln!(out, "!");
        let _ = writeln!(out, "ma={};{}", f.ma()[0], f.ma()[1]);
        let _ = writeln!(out, "mb={};{}", f.mb()[0], f.mb()[1]);
        let _ = writeln!(out, "n={}", f.n());
        let _ = writeln!(out, "relWidth={}", f.rel_width());
        let _ = writeln!(out, "maxAngle={}", f.max_angle());
        let _ = writeln!(out, "omegaLow={}", f.omega_low());
        if f.profile() != Profile::default() {
            let _ = writeln!(out, "profile={}", f.profile().name());
        }
        if f.depth() != DEFAULT_DEPTH {
            let _ = writeln!(out, "depth={}", f.depth());
        }
        if f.irregularity() != 0.0 {
            let _ = writeln!(out, "irregularity={}", f.irregularity());
        }
        if f.waviness() != 0.0 {
            let _ = writeln!(out, "waviness={}", f.waviness());
        }
        if f.seed() != i as u32 + 1 {
            let _ = writeln!(out, "seed={}", f.seed());
        }
        if f.space() != Space::default() {
            let _ = writeln!(out, "space={}", f.space().name());
        }
        if let Some(age) = &g.age {
            let _ = writeln!(out, "ageOnset={}", age.onset_years);
            let _ = writeln!(out, "ageFull={}", age.full_years);
            if age.shape != CurveShape::default() {
                let _ = writeln!(out, "ageShape={}", age.shape.name());
            }
        }
    }
    if !file.trailing_comments.is_empty() {
        out.push('\n');
        for c in &file.trailing_comments {
            let _ = writeln!(out, "#{c}");
        }
    }
    out
}

/// Writes `file` to `path` atomically (temporary file + rename).
pub fn save(file: &WrinkleFile, path: &Path) -> Result<(), Error> {
    crate::base::output_set::write_atomically(path, |w| {
        std::io::Write::write_all(w, write(file).as_bytes())
    })
}

#[cfg(test)]
mod tests;
