//! The frame-time governor: while the age plays, the view or a slider moves, the 3D view's
//! quality follows the measured frame interval to hold [`TARGET_MS`]; the first still
//! frame is drawn at full quality.
//!
//! The qualities are one table ([`LEVELS`]), from full to the cheapest: the resolution the
//! view is drawn at (then upscaled), every hair or one in the renderer's sparse stride, the
//! relief's parallax steps, the contact shadows, the size of the maps baked while moving. Each moving frame's interval feeds a
//! moving average; after a few frames at one level the governor steps down when the
//! average is over the target, and up when it is well under and the level above was not
//! measured too slow (each level's last average is kept: no see-saw between two levels).
//! A move starts at the level the last one ended at, so a slow machine starts slow.

/// The frame interval held while moving, ms (20 frames a second).
pub const TARGET_MS: f64 = 50.0;

/// One quality of the 3D view.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quality {
    /// Resolution of the view, 1 = full (the image is upscaled).
    pub scale: f32,
    /// One hair in the renderer's sparse stride is drawn.
    pub sparse_hair: bool,
    /// Parallax (relief) steps: linear search, binary refinement.
    pub relief_steps: (u32, u32),
    /// The contact shadows are drawn.
    pub shadows: bool,
    /// Side of the maps baked while moving, px (the worker shares the cores with the
    /// drawing; the still frame's bake is full size).
    pub preview_px: u32,
}

/// The qualities, full first. The still view is always the first.
pub const LEVELS: [Quality; 7] = [
    Quality {
        scale: 1.0,
        sparse_hair: false,
        relief_steps: (8, 4),
        shadows: true,
        preview_px: 512,
    },
    Quality {
        scale: 0.75,
        sparse_hair: false,
        relief_steps: (8, 4),
        shadows: false,
        preview_px: 512,
    },
    Quality {
        scale: 0.5,
        sparse_hair: true,
        relief_steps: (8, 4),
        shadows: false,
        preview_px: 512,
    },
    Quality {
        scale: 0.4,
        sparse_hair: true,
        relief_steps: (6, 3),
        shadows: false,
        preview_px: 384,
    },
    Quality {
        scale: 1.0 / 3.0,
        sparse_hair: true,
        relief_steps: (6, 3),
        shadows: false,
        preview_px: 384,
    },
    Quality {
        scale: 0.3,
        sparse_hair: true,
        relief_steps: (4, 2),
        shadows: false,
        preview_px: 256,
    },
    Quality {
        scale: 0.25,
        sparse_hair: true,
        relief_steps: (4, 2),
        shadows: false,
        preview_px: 192,
    },
];

/// The level a first move starts at (what the view used before the governor: a third of
/// the resolution, sparse hair).
const START_LEVEL: usize = 4;
/// Frames measured at a level before it may change.
const FRAMES_PER_DECISION: u32 = 4;
/// Frames after a change that are not measured (the change's own frame, its uploads).
const SETTLE_FRAMES: u32 = 1;
/// Over this share of the target: step down.
const SLOW: f64 = 1.1;
/// Under this share of the target: step up (if the level above was not measured slow).
const FAST: f64 = 0.65;
/// Weight of a new frame in the moving average.
const SMOOTHING: f64 = 0.35;

/// The governor's state.
#[derive(Clone, Debug)]
pub struct Governor {
    /// Whether the last frame was a moving one.
    moving: bool,
    /// The level in use (0: full, the still view).
    level: usize,
    /// The level the last move ended at.
    moving_level: usize,
    average_ms: Option<f64>,
    measured: u32,
    settle: u32,
    /// Each level's last moving average, ms.
    seen_ms: [Option<f64>; LEVELS.len()],
}

impl Default for Governor {
    fn default() -> Self {
        Self {
            moving: false,
            level: 0,
            moving_level: START_LEVEL,
            average_ms: None,
            measured: 0,
            settle: 0,
            seen_ms: [None; LEVELS.len()],
        }
    }
}

impl Governor {
    /// One frame: whether the view is moving and the interval since the previous frame,
    /// ms. Returns the quality to draw this frame at.
    pub fn frame(&mut self, moving: bool, interval_ms: f64) -> Quality {
        if !moving {
            if self.moving {
                self.moving_level = self.level;
            }
            self.moving = false;
            self.level = 0;
            self.restart();
            return LEVELS[0];
        }
        if !self.moving {
            // The first moving frame: where the last move ended.
            self.moving = true;
            self.level = self.moving_level;
            self.restart();
            return LEVELS[self.level];
        }
        if self.settle > 0 {
            self.settle -= 1;
            return LEVELS[self.level];
        }
        if !(interval_ms.is_finite() && interval_ms >= 0.0) {
            return LEVELS[self.level];
        }
        let avg = self
            .average_ms
            .map_or(interval_ms, |a| a + SMOOTHING * (interval_ms - a));
        self.average_ms = Some(avg);
        self.measured += 1;
        if self.measured >= FRAMES_PER_DECISION {
            self.seen_ms[self.level] = Some(avg);
            let last = LEVELS.len() - 1;
            if avg > TARGET_MS * SLOW && self.level < last {
                self.level += 1;
                self.restart();
            } else if avg < TARGET_MS * FAST
                && self.level > 0
                && self.seen_ms[self.level - 1].is_none_or(|ms| ms <= TARGET_MS)
            {
                self.level -= 1;
                self.restart();
            }
            self.moving_level = self.level;
        }
        LEVELS[self.level]
    }

    fn restart(&mut self) {
        self.average_ms = None;
        self.measured = 0;
        self.settle = SETTLE_FRAMES;
    }

    /// The quality in use.
    pub fn quality(&self) -> Quality {
        LEVELS[self.level]
    }

    /// The quality in use in words, for the status line.
    pub fn describe(&self) -> String {
        describe(&LEVELS[self.level], !self.moving)
    }
}

/// `q` in words, short enough for the status line: "full quality" when still, else what
/// the moving view draws ("moving: 25 %, relief 4+2, no shadows, maps 192²"; the hair
/// the status line says itself).
pub fn describe(q: &Quality, still: bool) -> String {
    if still {
        return "full quality".to_owned();
    }
    let (l, b) = q.relief_steps;
    let mut parts = vec![
        format!("{:.0} %", q.scale * 100.0),
        format!("relief {l}+{b}"),
    ];
    if !q.shadows {
        parts.push("no shadows".to_owned());
    }
    parts.push(format!("maps {}²", q.preview_px));
    format!("moving: {}", parts.join(", "))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The levels go from full to cheaper in every respect.
    #[test]
    fn each_level_costs_no_more_than_the_one_before() {
        assert_eq!(LEVELS[0].scale, 1.0);
        assert!(LEVELS[0].shadows && !LEVELS[0].sparse_hair);
        for w in LEVELS.windows(2) {
            let (a, b) = (w[0], w[1]);
            assert!(b.scale < a.scale, "{a:?} → {b:?}");
            assert!(b.sparse_hair >= a.sparse_hair && b.shadows <= a.shadows);
            assert!(b.relief_steps.0 <= a.relief_steps.0 && b.relief_steps.1 <= a.relief_steps.1);
            assert!(b.preview_px <= a.preview_px);
        }
    }

    /// Slow frames while moving lower the quality step by step to the cheapest; the first
    /// still frame is full again; the next move starts where the last one ended.
    #[test]
    fn slow_frames_lower_the_quality_and_a_still_frame_restores_it() {
        let mut g = Governor::default();
        assert_eq!(g.frame(false, 16.0), LEVELS[0]);
        let first = g.frame(true, 16.0);
        assert_eq!(first, LEVELS[START_LEVEL]);
        let mut scales = vec![first.scale];
        for _ in 0..100 {
            scales.push(g.frame(true, 200.0).scale);
        }
        assert!(scales.windows(2).all(|w| w[1] <= w[0]), "{scales:?}");
        assert_eq!(g.quality(), LEVELS[LEVELS.len() - 1]);
        assert_eq!(
            g.describe(),
            "moving: 25 %, relief 4+2, no shadows, maps 192²"
        );
        // Still: full at once.
        assert_eq!(g.frame(false, 200.0), LEVELS[0]);
        assert_eq!(g.describe(), "full quality");
        // The next move starts at the cheapest level it ended at.
        assert_eq!(g.frame(true, 200.0), LEVELS[LEVELS.len() - 1]);
    }

    /// Fast frames raise the quality up to full while moving (a real GPU draws every
    /// moving frame whole).
    #[test]
    fn fast_frames_raise_the_quality_to_full() {
        let mut g = Governor::default();
        g.frame(true, 5.0);
        for _ in 0..200 {
            g.frame(true, 5.0);
        }
        assert_eq!(g.quality(), LEVELS[0]);
    }

    /// A machine whose frame costs 8 ms plus 140 ms a full-resolution view (the pixels'
    /// share): the governor settles on a level that holds the target and stays there,
    /// without going back and forth.
    #[test]
    fn it_settles_on_a_level_that_holds_the_target() {
        let cost = |q: Quality| 8.0 + 140.0 * f64::from(q.scale * q.scale);
        let mut g = Governor::default();
        let mut q = g.frame(true, 16.0);
        let mut levels = Vec::new();
        for _ in 0..300 {
            q = g.frame(true, cost(q));
            levels.push(g.level);
        }
        let tail = &levels[200..];
        assert!(tail.iter().all(|&l| l == tail[0]), "{tail:?}");
        let settled = LEVELS[tail[0]];
        assert!(
            cost(settled) <= TARGET_MS,
            "{settled:?}: {} ms",
            cost(settled)
        );
        // The level above would not hold it.
        assert!(tail[0] > 0 && cost(LEVELS[tail[0] - 1]) > TARGET_MS * SLOW);
    }
}
