//! The fibre's parameters (docs/models.md §2 table): each wrinkle-file key with its range and
//! default, one table. The wrinkle file's checks, the fibre's setters, the editor's
//! inspector and the docs' table (a test reads it) all come from it.

use std::ops::RangeInclusive;

/// One parameter of a fibre.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FibreParam {
    /// The wrinkle file's key (and the inspector's label).
    pub key: &'static str,
    /// The valid range, inclusive.
    pub min: f32,
    pub max: f32,
    /// The value when the file gives none (`None`: required).
    pub default: Option<f32>,
    /// Whether only integers are valid.
    pub integer: bool,
    /// Whether a slider over the range is best logarithmic (it spans decades).
    pub wide: bool,
}

/// The number of wrinkles along the fibre, n (ω0 of [T]): [T] asks n > 1; agesim also takes
/// one wrinkle, a lone fold such as the nasolabial. Beyond 1000 a fibre is noise, not
/// wrinkles.
pub const N: FibreParam = FibreParam {
    key: "n",
    min: 1.0,
    max: 1000.0,
    default: None,
    integer: true,
    wide: true,
};
/// W, the capsule's half-width relative to the fibre's length: [T] keeps W ≤ 1; agesim lets
/// a one-wrinkle fibre reach further than its own length (a long line crossed by a short
/// fibre).
pub const REL_WIDTH: FibreParam = FibreParam {
    key: "relWidth",
    min: 1e-6,
    max: 10.0,
    default: Some(0.5),
    integer: false,
    wide: true,
};
/// αmax, the end-angle limit in units of π/2 (**Choice** 1.5: [T]'s table gives 0.25,
/// outside its own range; 1.5 is the value of [T]'s example file).
pub const MAX_ANGLE: FibreParam = FibreParam {
    key: "maxAngle",
    min: 1.0,
    max: 2.0,
    default: Some(1.5),
    integer: false,
    wide: false,
};
/// fmin, the relative frequency at the capsule's edge.
pub const OMEGA_LOW: FibreParam = FibreParam {
    key: "omegaLow",
    min: 0.0,
    max: 1.0,
    default: Some(0.5),
    integer: false,
    wide: false,
};
/// A, the fibre's relative amplitude (an agesim extension; [T] has A = 1).
pub const DEPTH: FibreParam = FibreParam {
    key: "depth",
    min: 0.0,
    max: 100.0,
    default: Some(1.0),
    integer: false,
    wide: true,
};
/// How unevenly deep the group's wrinkles are, between and along them.
pub const IRREGULARITY: FibreParam = FibreParam {
    key: "irregularity",
    min: 0.0,
    max: 1.0,
    default: Some(0.0),
    integer: false,
    wide: false,
};
/// How far the wrinkles wander, in periods.
pub const WAVINESS: FibreParam = FibreParam {
    key: "waviness",
    min: 0.0,
    max: 0.5,
    default: Some(0.0),
    integer: false,
    wide: false,
};

/// Every numeric parameter of a fibre, in the docs' order.
pub const FIBRE_PARAMS: [FibreParam; 7] = [
    N,
    REL_WIDTH,
    MAX_ANGLE,
    OMEGA_LOW,
    DEPTH,
    IRREGULARITY,
    WAVINESS,
];

/// Default W ([`REL_WIDTH`]).
pub const DEFAULT_REL_WIDTH: f32 = default_of(REL_WIDTH);
/// Default αmax ([`MAX_ANGLE`]).
pub const DEFAULT_MAX_ANGLE: f32 = default_of(MAX_ANGLE);
/// Default fmin ([`OMEGA_LOW`]).
pub const DEFAULT_OMEGA_LOW: f32 = default_of(OMEGA_LOW);
/// Default A ([`DEPTH`]).
pub const DEFAULT_DEPTH: f32 = default_of(DEPTH);

const fn default_of(p: FibreParam) -> f32 {
    match p.default {
        Some(v) => v,
        None => f32::NAN,
    }
}

/// Why a fibre parameter is invalid: the value's expected form, for error messages.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RangeError {
    /// What a valid value looks like, e.g. "a number in [1, 2]".
    pub expected: String,
}

impl FibreParam {
    /// The valid range, for a slider.
    pub fn range(&self) -> RangeInclusive<f32> {
        self.min..=self.max
    }

    /// The range as the docs' table writes it, e.g. `1e-6–10`.
    pub fn range_text(&self) -> String {
        format!("{}–{}", number(self.min), number(self.max))
    }

    /// What a valid value looks like, for error messages.
    pub fn expected(&self) -> String {
        if self.integer {
            format!("an integer in {}..={}", number(self.min), number(self.max))
        } else {
            format!("a number in [{}, {}]", number(self.min), number(self.max))
        }
    }

    /// `v` when it is finite and in range.
    pub fn check(&self, v: f32) -> Result<f32, RangeError> {
        if v.is_finite() && v >= self.min && v <= self.max {
            Ok(v)
        } else {
            Err(RangeError {
                expected: self.expected(),
            })
        }
    }
}

/// A bound as the docs write it: `1e-6` for tiny ones, else the shortest decimal.
fn number(v: f32) -> String {
    if v != 0.0 && v.abs() < 1e-3 {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

/// Validates an end point: two finite numbers.
pub fn check_point(p: [f32; 2]) -> Result<[f32; 2], RangeError> {
    if p.iter().all(|c| c.is_finite()) {
        Ok(p)
    } else {
        Err(RangeError {
            expected: "a UV point `u;v` of two finite numbers".into(),
        })
    }
}

/// Validates the wrinkle count ([`N`]).
pub fn check_count(n: i64) -> Result<u32, RangeError> {
    if (N.min as i64..=N.max as i64).contains(&n) {
        Ok(n as u32)
    } else {
        Err(RangeError {
            expected: N.expected(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::layers::wrinkles::muscle::Profile;

    #[test]
    fn the_messages_name_the_ranges() {
        assert_eq!(REL_WIDTH.expected(), "a number in [1e-6, 10]");
        assert_eq!(WAVINESS.expected(), "a number in [0, 0.5]");
        assert_eq!(N.expected(), "an integer in 1..=1000");
        assert_eq!(check_count(0).unwrap_err().expected, N.expected());
        assert!(check_count(1000).is_ok() && check_count(1001).is_err());
        assert!(DEPTH.check(f32::NAN).is_err() && DEPTH.check(100.0).is_ok());
    }

    /// The rows of the markdown table in `text` whose second cell names `key`, cells trimmed.
    fn rows<'a>(text: &'a str, key: &str) -> Vec<Vec<&'a str>> {
        let quoted = format!("`{key}`");
        text.lines()
            .filter(|l| l.starts_with('|'))
            .map(|l| l.split('|').map(str::trim).collect::<Vec<_>>())
            .filter(|cells| cells.iter().any(|c| c.split(", ").any(|k| k == quoted)))
            .collect()
    }

    /// docs/models.md §2's table and the wrinkle file's extension table give the ranges,
    /// defaults and profiles of this table and of [`Profile::ALL`].
    #[test]
    fn the_docs_tables_match_the_code() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/models.md");
        let docs = std::fs::read_to_string(&path).unwrap();
        for p in FIBRE_PARAMS {
            let found = rows(&docs, p.key);
            assert!(
                !found.is_empty(),
                "docs/models.md has no row for `{}`",
                p.key
            );
            let range = p.range_text();
            assert!(
                found.iter().any(|r| r.iter().any(|c| c.contains(&range))),
                "docs/models.md gives `{}` another range than {range}: {found:?}",
                p.key
            );
            if let Some(d) = p.default {
                let d = number(d);
                assert!(
                    found.iter().any(|r| r.iter().any(|c| *c == d)),
                    "docs/models.md gives `{}` another default than {d}: {found:?}",
                    p.key
                );
            }
        }
        let profiles = rows(&docs, "profile");
        assert!(profiles.len() >= 2, "{profiles:?}");
        for row in profiles {
            for profile in Profile::ALL {
                let name = format!("`{}`", profile.name());
                assert!(
                    row.iter().any(|c| c.contains(&name)),
                    "a docs/models.md profile row lacks {name}: {row:?}"
                );
            }
        }
    }
}
