//! The shape regions of the template (docs/models.md §13 table): where each descends,
//! deflates or bulges, by how many millimetres at full age, from when, and the rolls and
//! creases the old face forms (lid–cheek junction, nasolabial, marionette, jowl).

use super::*;

/// A region's age curve: linear from its onset to its full age (docs/models.md §13
/// "Regions": a smoothstep from 5 years later held the first descent back until the late
/// 40s, read blind as 25–38 at 45 on five of seven heads over rounds 22–31; linear to 80,
/// the rating's close-ups at 75 lost a tenth of the move, rounds 32–34).
pub(super) const fn curve(onset: f32, full: f32) -> AgeCurve {
    AgeCurve::new(onset, full, CurveShape::Linear)
}

/// How far past its full move a region of volume and sag goes in old age
/// (docs/models.md §13 "Old age"): its millimetres times this from
/// [`crate::age::LATE_END_YEARS`] on (`ShapeRegion::late`). The facial skeleton keeps receding after 65 (Shaw et al. 2011's
/// oldest group) and the soft tissue over it follows: a shape whole at 75 and still after
/// it read blind as 68–76 at 85 on four of seven heads (rounds 28–36).
pub const LATE_GAIN: f32 = 1.5;

impl ShapeRegion {
    /// The share of its full move at `years`: its curve times its old-age gain, 1 up to
    /// [`crate::age::LATE_START_YEARS`] and [`Self::late`] from
    /// [`crate::age::LATE_END_YEARS`] on, a smoothstep between (1.13 at 80, 1.37 at 85 for
    /// a gain of 1.5).
    pub fn factor(&self, years: f32) -> f32 {
        let curve = self.curve.factor(years);
        if self.late == 1.0 {
            return curve;
        }
        curve * (1.0 + (self.late - 1.0) * crate::age::old_age_share(years))
    }

    /// Each region's oldest share ([`Self::late`]), in [`REGIONS`] order.
    pub fn oldest() -> [f32; REGIONS.len()] {
        REGIONS.map(|r| r.late)
    }
}

/// The lid–cheek junction under each eye (its +x side; mirrored): from beside the inner
/// corner down and out under the eye's middle and up to below the outer corner.
pub(super) const LID_CHEEK_JUNCTION: [[f32; 3]; 5] = [
    [0.28, -0.2, 0.37],
    [0.4, -0.3, 0.32],
    [0.6, -0.36, 0.26],
    [0.8, -0.32, 0.22],
    [0.97, -0.2, 0.07],
];

/// The nasolabial folds of `nasolabial.wrk` on the template, from the nose wing down past
/// the mouth corner (measured: they are not mirror images about the eyes' midline, nor
/// are the nose and mouth on it), one per side. Each starts about 5 mm above the wing's
/// lateral point (alare), so the roll's faded end lies beside the wing and its crease
/// shows from the wing down (starting at alare, the fold read, blind, as "starting away
/// from the nose wing").
pub(super) const NASOLABIAL_R: [[f32; 3]; 9] = [
    [-0.47, -0.54, 0.39],
    [-0.49, -0.64, 0.38],
    [-0.543, -0.767, 0.385],
    [-0.59, -0.876, 0.4],
    [-0.637, -0.995, 0.416],
    [-0.662, -1.106, 0.43],
    [-0.655, -1.213, 0.44],
    [-0.677, -1.327, 0.42],
    [-0.7, -1.42, 0.4],
];

pub(super) const NASOLABIAL_L: [[f32; 3]; 9] = [
    [0.285, -0.59, 0.425],
    [0.31, -0.688, 0.418],
    [0.367, -0.798, 0.421],
    [0.425, -0.892, 0.438],
    [0.487, -1.011, 0.459],
    [0.524, -1.11, 0.468],
    [0.537, -1.2, 0.473],
    [0.602, -1.301, 0.435],
    [0.68, -1.4, 0.41],
];

/// The cheek over a nasolabial fold: a crest 4.5 mm high 7 mm from the line, falling back
/// over the next 45 mm, the cheek's breadth, with no crease of its own (the wrinkle file's
/// fold draws the crease). 6.5 mm high 12 mm out and falling back over 30 mm, its skirt
/// fell as steeply as the fold's wall (0.56 against 0.76 mm per mm, its lower end's lens
/// closing too, [`Roll::taper_at`]) and its outer edge read blind, on every head, as "a
/// second groove from the cheekbone to the jaw", "a cheek pad sealed off by a hard
/// groove" (round 17); now 0.43 against 0.75. Falling back over 12 mm (reach 0.5), with the depth gate
/// then at 0.2–0.4, its outer slope, on the side away from the key light, read blind on
/// every head as "a sharp dent, as if cut or bitten into the cheek", "starting too high
/// and too far out" (round 11; the depth gate widened with the reach, [`DEPTH_GATE`]:
/// narrower, it cut the broad skirt off along the cheek's depth contour). Blind,
/// this whole head scored 20.1 / 24 over sixteen raters, against 19.3 with the crest 4 mm
/// high 8.5 mm out and a 0.3 mm crease, whose steep narrow start read, from every rater,
/// as "a thin reddish cut or scar"; the fold itself still reads as "doubled brown-stained
/// streaks", and on the subject's right as "a pinched notch" (the roll's skirt ends in a
/// second line out on the cheek there, see [`relief`]).
///
/// Also tried: 3.5 mm high 5 mm from the crease, its wall lit from the other side read as
/// "a narrow dark slit", "a brown painted stripe"; 5 mm high 9.5 mm out, falling back over
/// 16.5 mm, it raised the skirt where the cheek turns away; over 42 mm it was still 2.6 mm
/// high where the cheek turns away and its depth gate cut it off there in a dimple; 6.5 mm
/// high 3 mm from the crease read as "a dark grimy blob by the mouth corner"; each rated
/// by eight, none better: a 0.2 mm crease over 2 mm, "a thin tinted slash"; 5.5 mm high
/// 7 mm out with half its relief finer than the triangles, "a brownish slit", the nose-to-
/// lip outline "kinked"; none of that relief and rising as a cube, "shallow, no cheek over
/// it" (the bags' roll rising so read as "stamped crescents").
pub(super) const CHEEK_ROLL: Roll = Roll {
    line: &[],
    raised: [1.0, 0.0],
    crest: 0.15,
    reach: 1.1,
    height_mm: 4.5,
    crease_mm: 0.0,
    crease_half: 0.03,
    mirrored: false,
    taper: Some([0.3, 0.5]),
    round: 0.04,
};

/// The marionette grooves of `marionette.wrk` on the template, from the mouth corner down
/// toward the jaw.
pub(super) const MARIONETTE_R: [[f32; 3]; 5] = [
    [-0.5, -1.37, 0.43],
    [-0.59, -1.48, 0.39],
    [-0.64, -1.66, 0.37],
    [-0.64, -1.85, 0.34],
    [-0.64, -1.98, 0.31],
];

pub(super) const MARIONETTE_L: [[f32; 3]; 5] = [
    [0.43, -1.35, 0.45],
    [0.56, -1.44, 0.41],
    [0.66, -1.59, 0.35],
    [0.72, -1.74, 0.28],
    [0.75, -1.84, 0.23],
];

/// A marionette groove from its second point on: the jowl's roll starts below the mouth
/// corner, where the cheek's roll over the nasolabial fold ends (from the corner, the two
/// rolls' ends met in a pit, read blind as "a dark grimy blob by the mouth corner").
pub(super) const fn below_the_mouth(line: &'static [[f32; 3]]) -> &'static [[f32; 3]] {
    match line.split_first() {
        Some((_, rest)) => rest,
        None => line,
    }
}

/// The jowl beside a marionette groove.
pub(super) const JOWL_ROLL: Roll = Roll {
    line: &[],
    raised: [1.0, 0.0],
    crest: 0.12,
    reach: 0.5,
    height_mm: 1.5,
    crease_mm: 0.0,
    crease_half: 0.06,
    mirrored: false,
    taper: None,
    round: 0.0,
};

/// The default regions (docs/models.md §13, each with its source). Millimetres at full
/// age; the face frame's unit is about 47 mm on an adult.
pub const REGIONS: [ShapeRegion; 11] = [
    ShapeRegion {
        name: "brows",
        what: "brow descent, most at its tail",
        blobs: &[Blob::new([0.75, 0.45, 0.25], [0.65, 0.35, 0.6])],
        motions: &[(Descent, 6.0)],
        rolls: &[],
        curve: curve(30.0, 75.0),
        late: 1.0,
    },
    ShapeRegion {
        name: "lids",
        what: "upper lids hooding",
        blobs: &[Blob::new([0.62, 0.14, 0.3], [0.5, 0.17, 0.45])],
        motions: &[(Descent, 1.5), (Bulge, 1.0)],
        rolls: &[],
        curve: curve(30.0, 75.0),
        late: 1.0,
    },
    ShapeRegion {
        name: "bags",
        what: "bags under the eyes",
        // The fat bulging under the lid, and its lower edge: a roll over the lid–cheek
        // junction, steep below (a blob alone, 5 mm, caught the frontal light as "a pale
        // crescent with no shadow under it", blind).
        // Two thirds of what they were (1.5 mm out and down, a 2.2 mm roll over a 0.5 mm
        // crease 3.8 mm to each side): with the contact shadows and the tear trough's
        // hollow under them, their lower edge read, blind, as "a hard dark arc painted low
        // on the cheek".
        blobs: &[Blob::new([0.62, -0.26, 0.3], [0.45, 0.18, 0.45])],
        motions: &[(Bulge, 1.0), (Descent, 1.0)],
        rolls: &[Roll {
            line: &LID_CHEEK_JUNCTION,
            raised: [0.0, 1.0],
            crest: 0.07,
            reach: 0.2,
            height_mm: 1.4,
            crease_mm: 0.3,
            crease_half: 0.11,
            mirrored: true,
            taper: None,
            round: 0.0,
        }],
        curve: curve(30.0, 70.0),
        late: LATE_GAIN,
    },
    ShapeRegion {
        name: "tear_trough",
        what: "tear trough, upper-lid sulcus, mid-cheek and submalar hollowing",
        // The tear trough; the sulcus between the upper lid's fold and the brow (the
        // orbit's rim shows); the malar fat of the mid-cheek, deflating as it descends
        // (blind ratings read the face without them as keeping its young volume).
        blobs: &[
            Blob::new([0.4, -0.42, 0.42], [0.32, 0.14, 0.4]),
            // The sulcus above the lid's fold, not the lid over the eyeball (which stays:
            // a deeper lid let the eye show through it as a dark fleck).
            Blob::new([0.55, 0.38, 0.2], [0.4, 0.12, 0.35]),
            // Broad: a blob 12 mm tall drew its lower edge, under the side light, as "a
            // pinched dent in mid-cheek" on the far side. A dish: with a plateau over its
            // inner third, the plateau's rim, 5 mm deep, drew a groove from beside the
            // nose down and out across the cheek on every head but the scan, read blind
            // as "a second nasolabial fold", "a V like the edge of a latex mask" (round
            // 12; gone when the region is off). Above the cheek's roll, where the malar fat
            // deflates, not over it: centred on the roll ([0.8, -0.6], 0.45 tall) it dug a
            // valley round the roll's outer edge, "a deep diagonal crease from under the eye
            // to the jaw" on every head (round 17; gone with the region off). 3 mm at its
            // centre: at 5 its lower edge ran into the submalar hollow below as one groove,
            // "the deepest groove runs down the outer cheek, from under the eye to the jaw,
            // and the fold from the nose wing stays faint", on all six MakeHuman heads from
            // all three reviewers (round 43; the fold 1.14, 1.43 at 3 mm, round 44).
            Blob::new([0.85, -0.45, 0.4], [0.55, 0.35, 0.5])
                .deflating(0.6)
                .soft(),
            // Below the cheekbone, lateral to the fold's cheek: the buccal hollow, broad
            // and 2.5 mm at its centre (18 mm across and 5 mm deep, its edge on the far
            // side of the light read, blind, as "a dark pit in the cheek"), a dish (a
            // plateau's rim drew a second fold out on the cheek on the side away from the
            // light). A third narrower and 3.5 mm deep, its front edge drew "a diagonal
            // groove from the outer cheekbone down to the jaw, far to the side of the
            // fold", "like a facet", on both European heads from all three reviewers
            // (rounds 45–46; gone with the blob off).
            Blob::new([1.25, -1.05, 0.05], [0.65, 0.65, 0.7])
                .deflating(0.5)
                .soft(),
        ],
        motions: &[(Deflate, 5.0)],
        rolls: &[],
        curve: curve(25.0, 65.0),
        late: LATE_GAIN,
    },
    ShapeRegion {
        name: "temples",
        what: "temples hollowing",
        // The temporal fossa behind the orbit's outer rim, not reaching the eye's corner
        // (the eye stays), so the outline from the front dips between the forehead and
        // the cheekbone (the fossa's dish narrower, its edge read, blind, as "a hard
        // vertical ridge"). A dish (a plateau's rim drew, blind, "a hard vertical ridge"
        // in the front outline), not reaching the forehead's side (where an edge read as
        // "a hard vertical step"), just behind the rim, where the hollow shows from the
        // front and at three-quarter (centred 68 mm out and 26 mm behind the eyes, and
        // 11 mm deep, every blind rater read "temples not hollow"), 15 mm deep: more than
        // an old temple loses, so that it shows at a portrait's size. A second dish over
        // the side of the head behind it (26 × 45 × 47 mm, 75 mm out, 38 mm behind), at
        // half the depth: at the full depth it cut the skull's side in under the unmoved
        // forehead, whose sides stood out as ridges, read blind as "temples that bulge
        // out into wings" on four heads of seven (round 56); without it as "temples
        // still full, the face puffy" (round 57; alone at 10 mm and farther back the
        // fossa's dish read as "only darkened, not hollowed").
        blobs: &[
            Blob::new([1.3, 0.45, -0.35], [0.42, 0.55, 0.45]).soft(),
            Blob::new([1.6, 0.5, -0.8], [0.55, 0.95, 1.0])
                .deflating(0.5)
                .soft(),
        ],
        motions: &[(Deflate, 15.0)],
        rolls: &[],
        curve: curve(30.0, 75.0),
        late: LATE_GAIN,
    },
    ShapeRegion {
        name: "cheeks",
        what: "cheeks descending over the nasolabial fold",
        // The malar fat pad (descending, barely fuller: blind ratings read a bulging
        // one as "fuller rather than thinned"), and the cheek rolling over each
        // nasolabial fold of the wrinkle file (blind ratings read the fold without it as
        // "a thin engraved crescent"; with a chain of blobs beside it, which swelled
        // evenly on all sides, as "a pencil line, no cheek hanging over it"). The pad a
        // dish: its plateau's rim, 5 mm down, sheared the cheek's coarse triangles into
        // "angular, faceted folds" round the roll on the European heads (round 18).
        blobs: &[Blob::new([0.8, -0.7, 0.3], [0.55, 0.5, 0.55])
            .bulging(0.2)
            .soft()],
        motions: &[(Descent, 5.0), (Bulge, 1.5)],
        rolls: &[
            Roll {
                line: &NASOLABIAL_R,
                raised: [-1.0, 0.0],
                ..CHEEK_ROLL
            },
            Roll {
                line: &NASOLABIAL_L,
                raised: [1.0, 0.0],
                ..CHEEK_ROLL
            },
        ],
        curve: curve(25.0, 70.0),
        late: LATE_GAIN,
    },
    ShapeRegion {
        name: "jowls",
        what: "jowls below the jaw line",
        blobs: &[Blob::new([0.95, -2.1, 0.0], [0.55, 0.62, 0.65])],
        motions: &[(Descent, 6.0), (Bulge, 1.0)],
        rolls: &[
            Roll {
                line: below_the_mouth(&MARIONETTE_R),
                raised: [-1.0, 0.0],
                ..JOWL_ROLL
            },
            Roll {
                line: below_the_mouth(&MARIONETTE_L),
                raised: [1.0, 0.0],
                ..JOWL_ROLL
            },
        ],
        curve: curve(30.0, 75.0),
        late: LATE_GAIN,
    },
    ShapeRegion {
        name: "lips",
        what: "upper lip lengthening and flattening",
        // The upper lip's skin, above the slit (the mouth's line at −1.34): it descends
        // over the red of the lip (which narrows) and flattens (blind ratings read it
        // unchanged as "puffy, sticking out past the lower lip in profile"). Nothing at
        // the slit: a deflation there parts the lips (their normals point at each other).
        // The lower lip's red thins too (its fullness deflates; vermilion height falls
        // with age, a strong cue of perceived age: Gunn et al. 2009): a blob centred
        // below the slit, reaching no nearer it than 0.08 (≈ 4 mm), rising (its border
        // toward the slit, which stays: the red's height falls; deflated only, the
        // African heads' full lower lips read, blind, as "thick and youthful", round 40).
        // Without it the panel heads' lips read, blind, as "as full as at 25". Rising
        // 1.6 × the region's descent (1 ×: 2 mm on the African man's 19 mm lower lip, "lips
        // still full", "a thick lower lip" on the African heads, rounds 44–49). Both lips'
        // red, the slit between them, move back together as their support recedes (a full lower lip, deflated only below its front, read, blind,
        // as "full, pouting lips that jut forward in profile" on the African heads,
        // rounds 28–29): a blob over the reds that neither descends nor deflates.
        blobs: &[
            Blob::new([0.0, -1.1, 0.5], [0.6, 0.24, 0.45]).retruding(0.0),
            Blob::new([0.0, -1.56, 0.5], [0.5, 0.14, 0.45])
                .descending(-1.6)
                .retruding(0.0),
            Blob::new([0.0, -1.37, 0.5], [0.45, 0.2, 0.45])
                .descending(0.0)
                .deflating(0.0),
        ],
        motions: &[(Descent, 1.5), (Deflate, 2.0), (Retrude, 2.0)],
        rolls: &[],
        curve: curve(30.0, 75.0),
        late: 1.0,
    },
    ShapeRegion {
        name: "nose",
        what: "nose tip drooping",
        // Over the lower nose, its wings and the columella down to the subnasale, so it
        // droops as one: over the tip alone (0.28 × 0.28 × 0.35), a broad, flat nose's
        // underside sheared between the dropped tip and the still wings and columella,
        // and unfolding it left the African heads' tips 0.2 mm of their 4.5.
        blobs: &[Blob::new([0.0, -0.65, 0.95], [0.45, 0.36, 0.45])],
        motions: &[(Descent, 4.5)],
        rolls: &[],
        curve: curve(35.0, 80.0),
        late: 1.0,
    },
    ShapeRegion {
        name: "ears",
        what: "earlobes lengthening",
        // The lower half of the ear, most at the lobe: the ear lengthens (a blob on the lobe
        // alone, 3 mm, read blind as "ears identical to the 25-year-old's").
        blobs: &[Blob::new([1.72, -1.0, -1.45], [0.35, 0.6, 0.45])],
        motions: &[(Descent, 8.0)],
        rolls: &[],
        curve: curve(30.0, 80.0),
        late: LATE_GAIN,
    },
    ShapeRegion {
        name: "neck",
        what: "submental laxity under the chin, platysmal bands and a wattle down the neck",
        // Under the chin (3 mm down: 5 mm, with the wattle, pinched the skin under the jaw
        // into a dark slit, read blind as "a gash under the chin"); the two platysmal
        // bands, vertical cords from under the chin down the front of the neck (a chain
        // each side), standing out 1.5 mm, not descending (narrower and descending with
        // the rest, their edges sheared the skin into "a sharp diagonal fold under the
        // chin", blind).
        blobs: &[
            Blob::new([0.0, -2.75, 0.05], [1.1, 0.5, 0.7]),
            Blob::new([0.3, -2.9, -0.75], [0.15, 0.35, 0.45])
                .bulging(3.0)
                .descending(0.0)
                .soft(),
            Blob::new([0.32, -3.25, -0.96], [0.15, 0.35, 0.45])
                .bulging(3.0)
                .descending(0.0)
                .soft(),
            // The wattle: the throat's skin at the angle of chin and neck hangs down 9 mm
            // and out 2 mm (blind: "in profile the neck is long, smooth and taut, no
            // wattle"), rounding the angle into an old throat's sagging line. A broad
            // dish, and mostly down: bulging 9 mm along the normals, it pushed the neck's
            // sides out too, and 12 mm down over a narrower dish sheared them, each read
            // blind as "a dark diagonal slash" from the front (and hung 12 mm lower under
            // a sharp angle, as "a ledge under the jaw").
            Blob::new([0.0, -2.9, -0.6], [1.3, 0.7, 0.5])
                .bulging(4.0)
                .descending(3.0)
                .soft(),
        ],
        motions: &[(Descent, 3.0), (Bulge, 0.5)],
        rolls: &[],
        curve: curve(30.0, 75.0),
        late: LATE_GAIN,
    },
];

/// The brows' place in [`REGIONS`].
pub const BROWS: usize = 0;
/// The upper lids' place in [`REGIONS`].
pub const LIDS: usize = 1;
/// The bags' place in [`REGIONS`].
pub const BAGS: usize = 2;
/// The index of the `lips` region in [`REGIONS`].
pub const LIPS: usize = 7;

/// The shadow under the bags at `q` (face frame, 0–1, at full age and strength): along
/// the lid–cheek junction, their roll's crease ([`Roll::shade`]). The skin colour draws
/// it, as the crease is narrower than a mesh's triangles (the nasolabial and marionette
/// rolls' creases are drawn by their wrinkle files).
pub fn drawn_crease(q: Vec3) -> f32 {
    REGIONS[BAGS]
        .rolls
        .iter()
        .map(|r| r.shade(q))
        .fold(0.0, f32::max)
}
