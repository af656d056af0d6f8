//! `agesim --soak SECONDS`: the real editor window driven for a long time as an artist
//! would, at random (seeded): slider drags over the layer fields, fibre drags, age scrubs,
//! undo and redo, wrinkle files rewritten on disk by "another program" (one rewrite in three
//! breaks the file, the next one mends it) and the mask touched. It checks, and prints as a
//! table:
//! - every bake request is answered (a request is answered when a bake of it, or of a newer
//!   request that superseded it, has reported), and how long that took;
//! - the resident memory once warm (the first moment past half time when every bake
//!   request so far has been answered, and again after each change of a setting that sizes
//!   the caches: the hair's density, a map's size, a feature count), at its highest and at
//!   the end (and each minute);
//! - no error but those of the broken file was shown.
//!
//! The SECONDS of actions count from the moment the first maps are up: on a slow machine
//! (a debug build on a loaded CI runner) the startup bake alone can take longer than a short
//! run, which then did nothing.
//!
//! A panic ends the process (the run fails). Growth over [`MAX_GROWTH_MIB`] from the warm
//! point to the end (before it the caches fill), a request not answered 60 s after the last action, or an
//! unexpected error fails the run: `agesim` then exits with an error ([`failed`]).

use std::collections::VecDeque;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// Memory growth from the warm point to the end of the run that fails it.
pub const MAX_GROWTH_MIB: f64 = 256.0;
/// How long the bakes have to answer once the actions stop.
const SETTLE: Duration = Duration::from_secs(60);

static FAILED: AtomicBool = AtomicBool::new(false);

/// Whether a soak run of this process failed (read by the command line after the window
/// closed).
pub fn failed() -> bool {
    FAILED.load(Ordering::SeqCst)
}

/// One thing the script does this frame.
#[derive(Clone, Debug, PartialEq)]
pub enum Action {
    None,
    /// Save the document into the soak's folder (once): its wrinkle files become files on
    /// disk that the editor watches.
    Setup,
    /// Move slider `field` (an index into the soak's fields) to `fraction` of its range.
    Field {
        field: usize,
        fraction: f32,
        dragging: bool,
    },
    /// Move a fibre's ends by `delta` UV (both ends, the same amount: a whole-fibre drag).
    Fibre {
        pick: u64,
        delta: [f32; 2],
        dragging: bool,
    },
    Age {
        t: f32,
        moving: bool,
    },
    Undo,
    Redo,
    /// Rewrite wrinkle file `pick` on disk: a fibre moved, or (`broken`) a line the parser
    /// refuses.
    RewriteWrinkles {
        pick: u64,
        broken: bool,
    },
    /// Write the mask file again (same pixels, new time).
    TouchMask,
    Quit,
}

/// An episode: one kind of action over some frames.
#[derive(Clone, Copy, Debug)]
enum Episode {
    Field { field: usize, from: f32, to: f32 },
    Fibre { pick: u64, step: [f32; 2] },
    Age { from: f32, to: f32 },
    Pause,
}

pub struct Soak {
    seconds: f64,
    fields: usize,
    start: Instant,
    /// When the first maps were up and the script started.
    script_start: Option<Instant>,
    rng: u64,
    set_up: bool,
    episode: Option<(Episode, u32, u32)>,
    /// A rewrite left a wrinkle file broken: the next one mends it.
    broken: bool,
    actions: [u64; 9],
    /// Requests not yet answered: (job id, when it was sent).
    pending: VecDeque<(u64, Instant)>,
    seen_latest: u64,
    answer_ms: Vec<f64>,
    /// The resident memory once warm, and when (seconds into the run).
    rss_warm: Option<(f64, f64)>,
    /// How many times a setting that sizes the caches changed (each restarts the warm-up).
    capacity_changes: u32,
    rss_max: f64,
    last_rss: Instant,
    frames: u64,
    errors_expected: usize,
    /// Slider values the project's rules refused (a value out of the range other fields
    /// allow): the editor says so and keeps the state; expected of random values.
    refused: usize,
    broken_rewrites: usize,
    reloads_seen: usize,
    errors_unexpected: Vec<String>,
    stopped: Option<Instant>,
    done: bool,
    minutes_printed: u64,
}

impl Soak {
    /// `fields`: how many slider fields the app offers the script.
    pub fn new(seconds: f64, fields: usize, seed: u64) -> Self {
        Self {
            seconds,
            fields,
            start: Instant::now(),
            script_start: None,
            rng: seed ^ 0x9e37_79b9_7f4a_7c15,
            set_up: false,
            episode: None,
            broken: false,
            actions: [0; 9],
            pending: VecDeque::new(),
            seen_latest: 0,
            answer_ms: Vec::new(),
            rss_warm: None,
            capacity_changes: 0,
            rss_max: 0.0,
            last_rss: Instant::now(),
            frames: 0,
            errors_expected: 0,
            refused: 0,
            broken_rewrites: 0,
            reloads_seen: 0,
            errors_unexpected: Vec::new(),
            stopped: None,
            done: false,
            minutes_printed: 0,
        }
    }

    /// splitmix64.
    fn next(&mut self) -> u64 {
        self.rng = self.rng.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.rng;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    fn unit(&mut self) -> f32 {
        (self.next() >> 40) as f32 / (1u64 << 24) as f32
    }

    /// An error the app showed: the broken file's and a refused slider value's (`refused`:
    /// shown while the script's slider edit was applied) are expected, any other fails
    /// the run. (An error can arrive after the file was mended: the file was read in
    /// between.)
    pub fn error_shown(&mut self, text: &str, broken_file: &str, refused: bool) {
        if refused {
            self.refused += 1;
        } else if !broken_file.is_empty() && text.contains(broken_file) {
            self.errors_expected += 1;
        } else {
            self.errors_unexpected.push(text.to_owned());
        }
    }

    /// A message the app showed: counts the reloads it reports.
    pub fn info_shown(&mut self, text: &str) {
        if text.starts_with("Reloaded") {
            self.reloads_seen += 1;
        }
    }

    /// Once per frame, with the newest job id sent and the newest that reported, and
    /// whether the maps are up (the script starts once they are). Returns what to do.
    pub fn frame(&mut self, latest: u64, reported: u64, ready: bool) -> Action {
        let now = Instant::now();
        self.frames += 1;
        self.observe(latest, reported);
        self.sample_memory(now);
        if self.done {
            return Action::None;
        }
        if !self.set_up {
            // The script starts once the first maps are up (later a layer switched off
            // may leave no map: that must not stop it).
            if !ready {
                return Action::None;
            }
            self.set_up = true;
            self.script_start = Some(now);
            return Action::Setup;
        }
        let elapsed = self.script_elapsed(now);
        if let Some(stopped) = self.stopped {
            if self.pending.is_empty() || now - stopped > SETTLE {
                self.done = true;
                self.report(now);
                return Action::Quit;
            }
            return Action::None;
        }
        if elapsed > self.seconds {
            self.stopped = Some(now);
            // A drag under way ends with its release (which bakes at full size).
            return match self.episode.take() {
                Some((episode, _, n)) => {
                    self.episode = Some((episode, n.saturating_sub(1), n));
                    self.step()
                }
                None => Action::None,
            };
        }
        self.step()
    }

    /// Notes the requests sent and answered: call after every action too, so a request
    /// is timed from when it was sent.
    pub fn observe(&mut self, latest: u64, reported: u64) {
        let now = Instant::now();
        if latest > self.seen_latest {
            self.seen_latest = latest;
            self.pending.push_back((latest, now));
        }
        while let Some(&(id, sent)) = self.pending.front() {
            if reported < id {
                break;
            }
            self.answer_ms.push((now - sent).as_secs_f64() * 1e3);
            self.pending.pop_front();
        }
    }

    fn step(&mut self) -> Action {
        if let Some((episode, k, n)) = self.episode {
            let last = k + 1 >= n;
            self.episode = (!last).then_some((episode, k + 1, n));
            let s = (k + 1) as f32 / n as f32;
            return match episode {
                Episode::Field { field, from, to } => Action::Field {
                    field,
                    fraction: from + (to - from) * s,
                    dragging: !last,
                },
                Episode::Fibre { pick, step } => Action::Fibre {
                    pick,
                    delta: step,
                    dragging: !last,
                },
                Episode::Age { from, to } => Action::Age {
                    t: from + (to - from) * s,
                    moving: !last,
                },
                Episode::Pause => Action::None,
            };
        }
        let frames = 3 + (self.next() % 18) as u32;
        let r = self.next() % 100;
        let kind = match r {
            0..30 => 0,
            30..50 => 1,
            50..70 => 2,
            70..80 => 3,
            80..85 => 4,
            85..93 => 5,
            93..96 => 6,
            _ => 7,
        };
        self.actions[kind] += 1;
        match kind {
            0 => {
                let field = (self.next() % self.fields.max(1) as u64) as usize;
                let from = self.unit();
                let to = (from + (self.unit() - 0.5) * 0.4).clamp(0.0, 1.0);
                self.episode = Some((Episode::Field { field, from, to }, 0, frames));
            }
            1 => {
                let pick = self.next();
                let step = [(self.unit() - 0.5) * 0.002, (self.unit() - 0.5) * 0.002];
                self.episode = Some((Episode::Fibre { pick, step }, 0, frames));
            }
            2 => {
                let from = self.unit();
                let to = self.unit();
                self.episode = Some((Episode::Age { from, to }, 0, frames));
            }
            3 => return Action::Undo,
            4 => return Action::Redo,
            5 => {
                // One rewrite in three breaks the file; a broken file is mended next.
                let broken = !self.broken && self.next().is_multiple_of(3);
                self.broken = broken;
                self.broken_rewrites += usize::from(broken);
                return Action::RewriteWrinkles {
                    pick: self.next(),
                    broken,
                };
            }
            6 => return Action::TouchMask,
            _ => self.episode = Some((Episode::Pause, 0, frames)),
        }
        Action::None
    }

    /// The script changed a setting that sizes the caches (the hair's density, a map's
    /// size): growth is measured again from once the bakes have caught up after it.
    /// Once the actions have stopped (the last drag released while settling), nothing
    /// restarts it: the growth since the warm point is measured.
    pub fn capacity_changed(&mut self) {
        if self.stopped.is_some() {
            return;
        }
        self.rss_warm = None;
        self.capacity_changes += 1;
    }

    fn sample_memory(&mut self, now: Instant) {
        if now - self.last_rss < Duration::from_secs(2) {
            return;
        }
        self.last_rss = now;
        let Some(rss) = resident_mib() else {
            return;
        };
        self.rss_max = self.rss_max.max(rss);
        let minute = ((now - self.start).as_secs_f64() / 60.0) as u64;
        if minute > self.minutes_printed {
            self.minutes_printed = minute;
            println!(
                "soak: {minute} min, {rss:.0} MiB resident, {} bake requests answered",
                self.answer_ms.len()
            );
        }
        // The first half fills the caches (every layer switched on once, the largest
        // hair counts seen), and nothing is full before the bakes have caught up: growth is
        // measured from the first moment past half time when every request so far has been
        // answered. (A short run's first full-size bake can land after its half: on a
        // loaded machine, at 16 s of a 20 s run, one was still to come, and its maps read
        // as 400–600 MiB of growth.)
        let elapsed = self.script_elapsed(now);
        if self.rss_warm.is_none()
            && elapsed > self.seconds * 0.5
            && !self.answer_ms.is_empty()
            && self.pending.is_empty()
        {
            self.rss_warm = Some((rss, (now - self.start).as_secs_f64()));
        }
    }

    /// Seconds since the script started (0 before the first maps are up).
    fn script_elapsed(&self, now: Instant) -> f64 {
        self.script_start
            .map_or(0.0, |start| (now - start).as_secs_f64())
    }

    fn report(&mut self, now: Instant) {
        let seconds = (now - self.start).as_secs_f64();
        let rss_end = resident_mib().unwrap_or(f64::NAN);
        // Never warm (the first bake answered in the last two seconds): no growth to
        // measure, and the table says so.
        let (warm, warm_at) = self.rss_warm.unwrap_or((rss_end, seconds));
        let growth = rss_end - warm;
        let answered = self.answer_ms.len();
        let unanswered = self.pending.len();
        self.answer_ms.sort_by(f64::total_cmp);
        let median = self
            .answer_ms
            .get(answered / 2)
            .copied()
            .unwrap_or(f64::NAN);
        let worst = self.answer_ms.last().copied().unwrap_or(f64::NAN);
        let a = self.actions;
        let first_maps = self
            .script_start
            .map_or(f64::NAN, |start| (start - self.start).as_secs_f64());
        println!(
            "| soak ({seconds:.0} s, {} frames; the first maps up after {first_maps:.0} s) | measured |",
            self.frames
        );
        println!("|---|---|");
        println!(
            "| actions | {} slider drags, {} fibre drags, {} age scrubs, {} undos, {} redos, {} wrinkle files rewritten on disk ({} of them broken, each mended by the next), {} mask touches, {} pauses; {} reloads reported by the editor |",
            a[0], a[1], a[2], a[3], a[4], a[5], self.broken_rewrites, a[6], a[7], self.reloads_seen
        );
        println!(
            "| bake requests answered | {answered} of {} (median {median:.0} ms, worst {worst:.0} ms after the request) |",
            answered + unanswered
        );
        println!(
            "| resident memory | {warm:.0} MiB once warm (at {warm_at:.0} s; {} changes of a setting that sizes the caches restarted the warm-up), {:.0} MiB at most, {rss_end:.0} MiB at the end (growth since {growth:+.0} MiB; limit {MAX_GROWTH_MIB:.0}) |",
            self.capacity_changes,
            self.rss_max.max(rss_end)
        );
        println!(
            "| errors shown | {} of the broken wrinkle files and {} slider values refused by the project's rules (both expected), {} other |",
            self.errors_expected,
            self.refused,
            self.errors_unexpected.len()
        );
        let mut problems = Vec::new();
        if unanswered > 0 {
            problems.push(format!(
                "{unanswered} bake requests unanswered after {SETTLE:?}"
            ));
        }
        if growth > MAX_GROWTH_MIB {
            problems.push(format!("memory grew {growth:.0} MiB"));
        }
        for e in &self.errors_unexpected {
            problems.push(format!("unexpected error: {e}"));
        }
        if problems.is_empty() {
            println!("soak passed");
        } else {
            for p in &problems {
                eprintln!("soak failed: {p}");
            }
            FAILED.store(true, Ordering::SeqCst);
        }
    }
}

/// The process's resident memory (Linux: `VmRSS` of `/proc/self/status`), MiB.
fn resident_mib() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmRSS:"))?;
    let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib / 1024.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_script_is_seeded_and_mixes_every_action() {
        let run = |seed| {
            let mut s = Soak::new(1e9, 10, seed);
            let mut out = Vec::new();
            for i in 0..4000 {
                out.push(s.frame(i, i, true));
            }
            (out, s.actions)
        };
        let (a, counts) = run(7);
        assert_eq!(a, run(7).0, "same seed, same script");
        assert_ne!(a, run(8).0);
        assert_eq!(a[0], Action::Setup);
        assert!(counts.iter().take(8).all(|&c| c > 0), "{counts:?}");
        // A drag ends with a release.
        let releases = a
            .iter()
            .filter(|x| {
                matches!(
                    x,
                    Action::Field {
                        dragging: false,
                        ..
                    }
                )
            })
            .count() as u64;
        // (The last drag may still be under way.)
        assert!(
            releases == counts[0] || releases + 1 == counts[0],
            "{releases}"
        );
    }

    #[test]
    fn a_request_is_answered_by_its_own_bake_or_a_newer_one() {
        let mut s = Soak::new(1e9, 1, 1);
        s.frame(1, 0, false);
        s.frame(3, 0, false);
        assert_eq!(s.pending.len(), 2);
        // Job 3 reports: 1 was superseded, both are answered.
        s.frame(3, 3, false);
        assert!(s.pending.is_empty());
        assert_eq!(s.answer_ms.len(), 2);
    }
}
