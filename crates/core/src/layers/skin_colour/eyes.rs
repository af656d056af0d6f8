//! Eyes drawn where a head's eyeballs read nothing but blank skin (docs/models.md "Skin
//! colour", "Eyes"). The panel's MakeHuman heads carry their eyeballs as parts of their one
//! OBJ, mapped onto an unpainted corner of the skin's map (their own eye texture is another
//! file): drawn with that map they were "orange blank eyes", read blind as a mask's. Where
//! an eyeball's texels are blank and no skin covers them, the 3D view draws an eye over
//! them, from where each texel lies on the ball: a pupil and an iris facing forward, a
//! sclera round them, and with age a yellower sclera and the arcus senilis, the pale ring
//! at the iris's rim (in 44 % of people over 60: the Tehran Geriatric Eye Study). The exported
//! colour map keeps the head's own texels: only the view draws the eyes.

use glam::{Vec2, Vec3};
use rayon::prelude::*;

use crate::base::cells::NearestPoints;
use crate::head::mesh::{Mesh, MeshPart};
use crate::maps::mask::HeadImage;
use crate::maps::raster::raster_uv;

use super::SurfaceTexels;

/// The angles from the eye's front (radians) of the pupil's rim, of the iris's and of the
/// dark limbal ring's half-width at that rim: a 2 mm pupil and a 5.9 mm iris on a 12 mm ball.
const PUPIL: f32 = 0.17;
const IRIS: f32 = 0.51;
const LIMBUS: f32 = 0.035;

/// The colours of an eye (sRGB, 0–1): the pupil, a brown iris (the commonest eye colour
/// the world over), the limbal ring, the young sclera and the old sclera's yellow, duller
/// (the old sclera yellows and muddies; kept near the young white, the African man's
/// eyes at 80 read blind as "bright white crescents", round 45), reached by
/// [`OLD_SCLERA_SHARE`] of the skin's paling curve.
const PUPIL_COLOUR: [f32; 3] = [0.05, 0.04, 0.04];
const IRIS_COLOUR: [f32; 3] = [0.30, 0.19, 0.12];
const LIMBUS_COLOUR: [f32; 3] = [0.13, 0.10, 0.08];
const SCLERA_COLOUR: [f32; 3] = [0.72, 0.68, 0.63];
const OLD_SCLERA_COLOUR: [f32; 3] = [0.62, 0.55, 0.42];
const OLD_SCLERA_SHARE: f32 = 0.6;
/// The arcus senilis: its colour and its width inside the iris's rim, radians.
const ARCUS_COLOUR: [f32; 3] = [0.70, 0.70, 0.68];
const ARCUS_WIDTH: f32 = 0.09;

/// Above this spread of lightness (standard deviation, 0–1) over an eyeball's texels they
/// hold a painted eye, which is kept (a painted eye spans a white sclera and a dark iris;
/// the panel's blank corner of skin spreads under 0.03).
const PAINTED_SPREAD: f32 = 0.08;

/// The lids' shade on the eye: the colour at their margin (a fraction of the eye's own) and
/// how far from the nearest skin (in the ball's radius) it clears, and how far round the
/// ball the lids are looked for. The lids and lashes keep light off the eye's edges (what a
/// digital human's "eye occlusion" shell draws); lit whole, the eyes read, blind, as
/// "glaring, bulging whites" on the dark heads.
const LID_SHADE: f32 = 0.5;
const LID_SHADE_WIDTH: f32 = 0.25;
const LID_REACH: f32 = 1.6;
/// An eye open at least this far (the largest distance, in the ball's radius, from the
/// lids to a point of the ball's front, about half the opening's height) takes the whole
/// [`LID_SHADE_WIDTH`]; a narrower one a shade narrowed in proportion, down to
/// [`LID_SHADE_NARROWEST`] of it. The panel's narrow eyes (the asian man's and
/// MakeHuman's, open 0.28–0.33 of their 15 mm balls) lay wholly in a shade made for wide
/// ones: read, blind, as "dark slits with no whites", "dead eyes" (rounds 25–29).
const LID_SHADE_OPEN: f32 = 0.4;
const LID_SHADE_NARROWEST: f32 = 0.5;
/// How far from the eye's front (radians) a texel counts toward the opening's measure.
const OPENING_FRONT: f32 = 0.6;

/// Guard band round each eyeball's UV triangles, pixels (the map's bilinear filtering).
const GUARD_PX: f32 = 1.5;

/// The texels of a head's blank eyeballs and where each lies on its ball.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct EyeTexels {
    size: u32,
    /// Texel index, its angle from the eye's front (radians) and round it (radians), and
    /// how far it is from the lids' shade (0 at the lid's margin, 1 clear of it).
    texels: Vec<(u32, f32, f32, f32)>,
}

impl EyeTexels {
    /// The texels of `mesh`'s eyeballs ([`is_eyeball`]) in its UV layout at `size`² that
    /// no skin covers (`skin`: the skin's texels at that size), found on `image` (the colour
    /// map at that size) to be blank. The eye looks through its lids' opening, forward (+z,
    /// the scene's frame) give or take 20° ([`gaze`]).
    pub fn new(mesh: &Mesh, size: u32, skin: Option<&SurfaceTexels>, image: &HeadImage) -> Self {
        let n = size as usize;
        let mut texels = Vec::new();
        if image.width_px != size
            || image.height_px != size
            || mesh.uvs().is_empty()
            || !mesh.parts().iter().any(is_eyeball)
        {
            return Self { size, texels };
        }
        let (positions, uvs, indices) = (mesh.positions(), mesh.uvs(), mesh.indices());
        let skin_points: Vec<Vec3> = {
            let mut on_skin = vec![false; positions.len()];
            for &i in mesh.skin_indices().iter() {
                on_skin[i as usize] = true;
            }
            (0..positions.len())
                .filter(|&i| on_skin[i])
                .map(|i| positions[i])
                .collect()
        };
        let skin_triangles = mesh.skin_indices();
        for part in mesh.parts().iter().filter(|p| is_eyeball(p)) {
            let first = part.first_triangle as usize * 3;
            let Some(tris) = indices.get(first..first + part.triangle_count as usize * 3) else {
                continue;
            };
            // The ball: its box's centre in x and y, its front less its radius in z (a
            // ball cut off behind is still centred on its front).
            let (lo, hi) = tris.iter().fold(
                (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
                |(lo, hi), &i| (lo.min(positions[i as usize]), hi.max(positions[i as usize])),
            );
            let radius = 0.25 * ((hi.x - lo.x) + (hi.y - lo.y));
            if !(radius > 0.0 && radius.is_finite()) {
                continue;
            }
            let centre = Vec3::new(0.5 * (lo.x + hi.x), 0.5 * (lo.y + hi.y), hi.z - radius);
            let (gaze, across, up) = gaze(centre, radius, positions, &skin_triangles);
            // The skin round the ball (the lids): a texel near it is in the lids' shade.
            let lids: Vec<Vec3> = skin_points
                .iter()
                .copied()
                .filter(|p| p.distance(centre) < LID_REACH * radius)
                .collect();
            // (texel, the point it stands for), then (texel, from the front, round,
            // distance to the lids), the last in parallel in the texels' order, each
            // texel's nearest lid point looked for in the cubes round it (among all of
            // them, it was a second of opening a 570k-triangle head).
            let lids = NearestPoints::new(&lids, LID_REACH * radius / 16.0);
            let mut points: Vec<(u32, Vec3)> = Vec::new();
            for t in tris.chunks_exact(3) {
                let v = [0, 1, 2].map(|k| t[k] as usize);
                let (Some(a), Some(b), Some(c)) = (uvs.get(v[0]), uvs.get(v[1]), uvs.get(v[2]))
                else {
                    continue;
                };
                let p = v.map(|i| positions[i]);
                raster_uv([*a, *b, *c], size, GUARD_PX, |x, y, w, _| {
                    let i = y * n + x;
                    if skin.is_some_and(|s| s.covers_skin(i)) {
                        return;
                    }
                    points.push((i as u32, p[0] * w[0] + p[1] * w[1] + p[2] * w[2]));
                });
            }
            let mut own: Vec<(u32, f32, f32, f32)> = points
                .par_iter()
                .with_min_len(256)
                .filter_map(|&(i, at)| {
                    let d = (at - centre).normalize_or_zero();
                    if d == Vec3::ZERO {
                        return None;
                    }
                    let from_front = d.dot(gaze).clamp(-1.0, 1.0).acos();
                    let round = d.dot(up).atan2(d.dot(across));
                    Some((i, from_front, round, lids.distance(at)))
                })
                .collect();
            let opening = own
                .iter()
                .filter(|t| t.1 < OPENING_FRONT)
                .map(|t| t.3)
                .fold(0.0f32, f32::max);
            let width = shade_width(radius, opening);
            for t in &mut own {
                t.3 = smooth(t.3 / width);
            }
            own.sort_by_key(|t| t.0);
            own.dedup_by_key(|t| t.0);
            if !painted(image, &own) {
                texels.extend(own);
            }
        }
        Self { size, texels }
    }

    /// Whether there is no eye to draw.
    pub fn is_empty(&self) -> bool {
        self.texels.is_empty()
    }

    /// Draws the eyes over `image` (sRGB RGBA8 at the texels' size; alpha kept) at an
    /// age: `old` 0–1, the skin's paling and yellowing curve (the sclera yellows with it,
    /// and the arcus grows over its second half).
    pub fn draw(&self, image: &mut HeadImage, old: f32) {
        if image.width_px != self.size || image.height_px != self.size {
            return;
        }
        let old = old.clamp(0.0, 1.0);
        let arcus = smooth((old - 0.35) / 0.55);
        for &(i, from_front, round, clear) in &self.texels {
            let c =
                eye_colour(from_front, round, old, arcus) * (LID_SHADE + (1.0 - LID_SHADE) * clear);
            if let Some(px) = image.rgba.get_mut(i as usize * 4..i as usize * 4 + 3) {
                for (p, c) in px.iter_mut().zip(c.to_array()) {
                    *p = (c.clamp(0.0, 1.0) * 255.0).round() as u8;
                }
            }
        }
    }
}

/// How far from the lids (mesh units) their shade clears on a ball of `radius` whose front
/// lies at most `opening` from the lids ([`LID_SHADE_OPEN`]).
fn shade_width(radius: f32, opening: f32) -> f32 {
    let open = (opening / (LID_SHADE_OPEN * radius)).clamp(LID_SHADE_NARROWEST, 1.0);
    (LID_SHADE_WIDTH * radius * open).max(f32::MIN_POSITIVE)
}

/// Where an eye looks, and the two directions across its front (toward +x and +y): through
/// the middle of the opening its lids leave on the ball, seen from the front (`skin`: the
/// skin's triangles), a little above it (the pupil lies nearer the upper lid than the
/// lower: MRD1 about 4 mm, MRD2 about 5.5 mm), at most [`GAZE_MOST`] from straight ahead;
/// straight ahead (+z) where no skin lies round the ball or the lids leave less than
/// [`GAZE_SAMPLES_LEAST`] of the front open. A helper eyeball that a head's shape moved
/// away from (the panel's African man's sits 2.5 mm above his lids' opening) looked at its
/// own +z: its iris hid under the upper lid, and with the lids' age under it whole, read
/// blind as "bright white eye slits".
fn gaze(centre: Vec3, radius: f32, positions: &[Vec3], skin: &[u32]) -> (Vec3, Vec3, Vec3) {
    let straight = (Vec3::Z, Vec3::X, Vec3::Y);
    let reach = GAZE_LID_REACH * radius;
    let near: Vec<[Vec3; 3]> = skin
        .chunks_exact(3)
        .filter_map(|t| {
            let p = [0, 1, 2].map(|k| positions.get(t[k] as usize).copied());
            let p = [p[0]?, p[1]?, p[2]?];
            // Only skin in front of the ball's middle can cover its front.
            (p.iter().any(|q| q.distance(centre) < reach) && p.iter().any(|q| q.z > centre.z))
                .then_some(p)
        })
        .collect();
    if near.is_empty() {
        return straight;
    }
    let front = Front::new(near, centre, radius);
    let steps = GAZE_STEPS as i32;
    let (mut sum, mut count, mut low, mut high) = (Vec3::ZERO, 0u32, 1.0f32, -1.0f32);
    for j in -steps..=steps {
        for i in -steps..=steps {
            let (x, y) = (i as f32 / steps as f32, j as f32 / steps as f32);
            let z2 = 1.0 - x * x - y * y;
            if z2 < 0.05 {
                continue;
            }
            let d = Vec3::new(x, y, z2.sqrt());
            if !front.covered(centre + radius * d) {
                sum += d;
                count += 1;
                low = low.min(y);
                high = high.max(y);
            }
        }
    }
    if count < GAZE_SAMPLES_LEAST {
        return straight;
    }
    let mean = sum / count as f32 + Vec3::Y * (GAZE_ABOVE * (high - low));
    let Some(g) = mean.try_normalize() else {
        return straight;
    };
    let turn = g.z.clamp(-1.0, 1.0).acos();
    let g = if turn > GAZE_MOST {
        let side = Vec3::new(g.x, g.y, 0.0).normalize_or_zero();
        (Vec3::Z * GAZE_MOST.cos() + side * GAZE_MOST.sin()).normalize()
    } else {
        g
    };
    let across = (Vec3::X - g * g.x).normalize_or(Vec3::X);
    (g, across, g.cross(across))
}

/// The skin before an eyeball ([`gaze`]), sorted into cells of the square before the ball
/// by the triangles' boxes across the view (padded, so that rounding cannot leave one out
/// of a cell it covers): a point tests its own cell's triangles, with the answer of
/// testing them all (testing all of them was half a second of opening a 570k-triangle
/// head).
struct Front {
    near: Vec<[Vec3; 3]>,
    cells: Vec<Vec<u32>>,
    corner: Vec2,
    cell: f32,
    radius: f32,
}

impl Front {
    fn new(near: Vec<[Vec3; 3]>, centre: Vec3, radius: f32) -> Self {
        let mut front = Self {
            cells: vec![Vec::new(); GAZE_CELLS * GAZE_CELLS],
            corner: Vec2::new(centre.x - radius, centre.y - radius),
            cell: 2.0 * radius / GAZE_CELLS as f32,
            radius,
            near: Vec::new(),
        };
        let pad = Vec3::splat(1e-3 * radius);
        let far = front.corner + Vec2::splat(2.0 * radius);
        for (k, p) in near.iter().enumerate() {
            let (lo, hi) = (
                p[0].min(p[1]).min(p[2]) - pad,
                p[0].max(p[1]).max(p[2]) + pad,
            );
            if hi.x < front.corner.x || hi.y < front.corner.y || lo.x > far.x || lo.y > far.y {
                continue;
            }
            let ([i0, j0], [i1, j1]) = (front.at(lo), front.at(hi));
            for j in j0..=j1 {
                for i in i0..=i1 {
                    front.cells[j * GAZE_CELLS + i].push(k as u32);
                }
            }
        }
        front.near = near;
        front
    }

    /// The cell of a point's x and y (clamped to the square).
    fn at(&self, p: Vec3) -> [usize; 2] {
        let index = |v: f32| ((v / self.cell).floor().max(0.0) as usize).min(GAZE_CELLS - 1);
        [index(p.x - self.corner.x), index(p.y - self.corner.y)]
    }

    /// Whether a ray from `at` toward the viewer (+z) passes through a skin triangle.
    fn covered(&self, at: Vec3) -> bool {
        let [i, j] = self.at(at);
        self.cells[j * GAZE_CELLS + i]
            .iter()
            .any(|&k| covers(&self.near[k as usize], at, self.radius))
    }
}

/// Whether the ray from `at` toward the viewer (+z) passes through triangle `p` (a ball
/// of `radius`: the scale of what is degenerate).
fn covers([a, b, c]: &[Vec3; 3], at: Vec3, radius: f32) -> bool {
    let (e0, e1, e2) = (*b - *a, *c - *a, at - *a);
    let den = e0.x * e1.y - e1.x * e0.y;
    if den.abs() < f32::EPSILON * radius * radius {
        return false;
    }
    let u = (e2.x * e1.y - e1.x * e2.y) / den;
    let w = (e0.x * e2.y - e2.x * e0.y) / den;
    u >= 0.0 && w >= 0.0 && u + w <= 1.0 && a.z + u * e0.z + w * e1.z > at.z
}

/// The gaze's measure ([`gaze`]): the skin looked at round the ball (in its radius), the
/// samples across the ball's front (2 × this + 1 a side), the fewest open ones, how far
/// above the opening's middle the pupil lies (a share of the opening's height) and the
/// most the gaze turns from straight ahead (radians).
const GAZE_LID_REACH: f32 = 2.0;
const GAZE_STEPS: u32 = 24;
/// The cells a side of the square before the ball that [`gaze`] sorts the skin into.
const GAZE_CELLS: usize = 24;
const GAZE_SAMPLES_LEAST: u32 = 12;
const GAZE_ABOVE: f32 = 0.08;
const GAZE_MOST: f32 = 0.35;

/// Whether a part is an eyeball (an eye, its cornea, iris, pupil or sclera), not the wet,
/// shadow or hair parts round it (lacrimal, tear line, occlusion, blend, lashes, brows) nor
/// an eye socket (the default head's, inside its closed lids).
pub fn is_eyeball(part: &MeshPart) -> bool {
    let name = part.name.to_lowercase();
    let what = name
        .split_once(" material ")
        .map_or(name.as_str(), |(_, m)| m);
    ["eye", "cornea", "iris", "pupil", "sclera"]
        .iter()
        .any(|w| what.contains(w))
        && ![
            "lash",
            "brow",
            "lacrimal",
            "tear",
            "occlusion",
            "blend",
            "shadow",
            "caruncle",
            "lid",
            "socket",
        ]
        .iter()
        .any(|w| what.contains(w))
}

/// Whether `texels` of `image` hold a painted eye (their lightness spreads over
/// [`PAINTED_SPREAD`]).
fn painted(image: &HeadImage, texels: &[(u32, f32, f32, f32)]) -> bool {
    if texels.is_empty() {
        return false;
    }
    let lum: Vec<f32> = texels
        .iter()
        .filter_map(|&(i, ..)| image.rgba.get(i as usize * 4..i as usize * 4 + 3))
        .map(|p| {
            (0.2126 * f32::from(p[0]) + 0.7152 * f32::from(p[1]) + 0.0722 * f32::from(p[2])) / 255.0
        })
        .collect();
    let mean = lum.iter().sum::<f32>() / lum.len() as f32;
    let var = lum.iter().map(|l| (l - mean).powi(2)).sum::<f32>() / lum.len() as f32;
    var.sqrt() > PAINTED_SPREAD
}

/// The eye's colour (sRGB, 0–1) `from_front` radians from its front, `round` radians round
/// it, at `old` (the sclera's yellowing) with the arcus at `arcus` (0–1).
fn eye_colour(from_front: f32, round: f32, old: f32, arcus: f32) -> Vec3 {
    // The sclera dims toward the corners, where the lids and the caruncle shade it and its
    // vessels show (an even white read, blind, as "glowing whites of the eyes" on dark
    // skin).
    let sclera = Vec3::from(SCLERA_COLOUR)
        .lerp(Vec3::from(OLD_SCLERA_COLOUR), OLD_SCLERA_SHARE * old)
        * (1.0 - 0.3 * smooth((from_front - 0.7) / 0.6));
    // The iris: fibres radiating from the pupil (a lighter collarette round it, darker
    // toward the rim), the limbal ring blending it into the sclera.
    let fibres = 0.85
        + 0.1 * (round * 23.0).sin()
        + 0.06 * (round * 57.0 + 1.3).sin()
        + 0.04 * (round * 131.0 + 0.4).sin();
    let across = ((from_front - PUPIL) / (IRIS - PUPIL)).clamp(0.0, 1.0);
    let collarette = 1.0 + 0.35 * (1.0 - smooth((across - 0.15) / 0.25));
    let iris = Vec3::from(IRIS_COLOUR) * fibres * collarette * (1.0 - 0.25 * across);
    let iris = iris.lerp(
        Vec3::from(ARCUS_COLOUR),
        0.75 * arcus * smooth((from_front - (IRIS - ARCUS_WIDTH)) / (0.5 * ARCUS_WIDTH)),
    );
    let limbus = Vec3::from(LIMBUS_COLOUR);
    let to_limbus = 1.0 - smooth((from_front - IRIS).abs() / LIMBUS);
    let eye = if from_front < IRIS { iris } else { sclera };
    let eye = eye.lerp(limbus, 0.7 * to_limbus);
    let pupil = 1.0 - smooth((from_front - PUPIL) / 0.03 + 0.5);
    eye.lerp(Vec3::from(PUPIL_COLOUR), pupil)
}

/// A smoothstep over [0, 1].
fn smooth(x: f32) -> f32 {
    let x = x.clamp(0.0, 1.0);
    x * x * (3.0 - 2.0 * x)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The cells before the ball give the answer of testing every triangle, for points all
    /// over its front and triangles of every size, some reaching past the square.
    #[test]
    fn the_front_s_cells_hold_every_triangle_that_covers_a_point() {
        let mut rng = crate::base::rng::Rng::new(7);
        let (centre, radius) = (Vec3::new(0.3, -0.2, 1.0), 0.012);
        let mut r = |scale: f32| (rng.next_f32() * 2.0 - 1.0) * scale;
        let near: Vec<[Vec3; 3]> = (0..150)
            .map(|k| {
                let size = radius * [0.05, 0.3, 1.5][k % 3];
                let at = centre + Vec3::new(r(1.6 * radius), r(1.6 * radius), r(radius));
                [0; 3].map(|_| at + Vec3::new(r(size), r(size), r(size)))
            })
            .collect();
        let front = Front::new(near.clone(), centre, radius);
        let (mut covered, steps) = (0, 60);
        for j in -steps..=steps {
            for i in -steps..=steps {
                let at = centre
                    + radius * Vec3::new(i as f32 / steps as f32, j as f32 / steps as f32, 0.2);
                let all = near.iter().any(|p| covers(p, at, radius));
                assert_eq!(front.covered(at), all, "at {at}");
                covered += usize::from(all);
            }
        }
        assert!(
            covered > 1000 && covered < 13000,
            "{covered} of 14641 covered"
        );
    }

    fn part(name: &str) -> MeshPart {
        MeshPart {
            name: name.into(),
            first_triangle: 0,
            triangle_count: 0,
        }
    }

    #[test]
    fn eyeballs_are_told_from_what_lies_round_them() {
        for name in [
            "object \"eye_l\"",
            "object \"Head\" material \"Cornea\"",
            "mesh \"CC_Base_Eye\" primitive 0",
        ] {
            assert!(is_eyeball(&part(name)), "{name}");
        }
        for name in [
            "object \"head\"",
            "object \"Head\" material \"EyeBlend\"",
            "object \"eyelashes\"",
            "object \"Head\" material \"lacrimal fluid\"",
            "object \"eye occlusion\"",
            "object \"eyebrow_l\"",
            "mesh \"eye sockets (inside the closed lids)\" primitive 0",
        ] {
            assert!(!is_eyeball(&part(name)), "{name}");
        }
    }

    #[test]
    fn the_eye_has_a_dark_pupil_a_brown_iris_and_a_white_sclera_which_yellows() {
        let lum = |c: Vec3| c.dot(Vec3::new(0.2126, 0.7152, 0.0722));
        let young = |a: f32| eye_colour(a, 0.3, 0.0, 0.0);
        assert!(lum(young(0.0)) < 0.06);
        let iris = young(0.35);
        assert!(iris.x > iris.z && lum(iris) < 0.35, "{iris}");
        assert!(lum(young(0.7)) > 0.6);
        let old = eye_colour(0.7, 0.3, 1.0, 1.0);
        assert!(old.z < young(0.7).z - 0.05, "{old} {}", young(0.7));
        // The arcus: the iris's rim pales with age, its middle does not.
        let rim = IRIS - 0.3 * ARCUS_WIDTH;
        assert!(lum(eye_colour(rim, 0.3, 1.0, 1.0)) > lum(eye_colour(rim, 0.3, 0.0, 0.0)) + 0.2);
        assert!((lum(eye_colour(0.3, 0.3, 1.0, 1.0)) - lum(young(0.3))).abs() < 0.01);
    }

    /// A ball of radius 1 at the origin behind lids that leave open a slot from `low` to
    /// `high` (in y), as two quads of skin in front of it.
    fn lids(low: f32, high: f32) -> (Vec<Vec3>, Vec<u32>) {
        let quad = |y0: f32, y1: f32| {
            [
                Vec3::new(-1.5, y0, 1.2),
                Vec3::new(1.5, y0, 1.2),
                Vec3::new(1.5, y1, 1.2),
                Vec3::new(-1.5, y1, 1.2),
            ]
        };
        let positions: Vec<Vec3> = [quad(high, 1.5), quad(-1.5, low)].concat();
        let indices = vec![0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7];
        (positions, indices)
    }

    #[test]
    fn an_eye_looks_through_its_lids_opening() {
        // Open from 0.6 below the middle to 0.1 below: the pupil a little above the slot's
        // middle (-0.35), never more than 20° off.
        let (positions, skin) = lids(-0.6, -0.1);
        let (g, across, up) = gaze(Vec3::ZERO, 1.0, &positions, &skin);
        assert!(g.y < -0.25 && g.y > -GAZE_MOST.sin() - 1e-4, "{g}");
        assert!(g.x.abs() < 1e-3, "{g}");
        assert!(across.dot(g).abs() < 1e-5 && up.dot(g).abs() < 1e-5 && up.y > 0.9);
        // Open round the middle: straight ahead, nudged up.
        let (positions, skin) = lids(-0.4, 0.4);
        let (g, ..) = gaze(Vec3::ZERO, 1.0, &positions, &skin);
        assert!(g.y > 0.0 && g.y < 0.1, "{g}");
        // No lids, or lids shut: straight ahead.
        assert_eq!(gaze(Vec3::ZERO, 1.0, &positions, &[]).0.y, 0.0);
        let (positions, skin) = lids(-0.2, -0.2);
        assert_eq!(gaze(Vec3::ZERO, 1.0, &positions, &skin).0, Vec3::Z);
    }

    #[test]
    fn the_lids_shade_the_eye_s_edges() {
        let eyes = EyeTexels {
            size: 2,
            texels: vec![(0, 0.9, 0.0, 0.0), (1, 0.9, 0.0, 1.0)],
        };
        let mut image = HeadImage {
            width_px: 2,
            height_px: 2,
            rgba: vec![0; 16],
        };
        eyes.draw(&mut image, 0.0);
        let (at_lid, clear) = (f32::from(image.rgba[0]), f32::from(image.rgba[4]));
        assert!(
            at_lid < 0.6 * clear,
            "{at_lid} at the lid, {clear} clear of it"
        );
    }

    /// A wide-open eye keeps the whole shade; a narrow one's clears nearer the lids, in
    /// proportion, never under half of it.
    #[test]
    fn a_narrow_eye_s_lid_shade_is_narrower() {
        let r = 15.0;
        let full = LID_SHADE_WIDTH * r;
        assert_eq!(shade_width(r, 0.45 * r), full);
        assert_eq!(shade_width(r, LID_SHADE_OPEN * r), full);
        let narrow = shade_width(r, 0.28 * r);
        assert!((narrow - 0.7 * full).abs() < 1e-4, "{narrow} of {full}");
        assert_eq!(shade_width(r, 0.05 * r), LID_SHADE_NARROWEST * full);
        assert!(shade_width(r, 0.0) > 0.0);
    }

    #[test]
    fn a_painted_eye_is_kept_and_a_blank_one_drawn() {
        let mut image = HeadImage {
            width_px: 4,
            height_px: 4,
            rgba: vec![180; 64],
        };
        let texels: Vec<(u32, f32, f32, f32)> =
            (0..16).map(|i| (i, 0.1 * i as f32, 0.0, 1.0)).collect();
        assert!(!painted(&image, &texels));
        for i in 0..8 {
            image.rgba[i * 4..i * 4 + 3].copy_from_slice(&[20, 20, 20]);
        }
        assert!(painted(&image, &texels));
        let eyes = EyeTexels { size: 4, texels };
        let mut blank = HeadImage {
            width_px: 4,
            height_px: 4,
            rgba: vec![180; 64],
        };
        eyes.draw(&mut blank, 0.0);
        assert!(blank.rgba[0] < 30, "the pupil: {:?}", &blank.rgba[..4]);
        assert!(
            blank.rgba[8 * 4] > 160,
            "the sclera: {:?}",
            &blank.rgba[32..36]
        );
        // Dimmer toward the corners.
        assert!(blank.rgba[15 * 4] < blank.rgba[8 * 4] - 30);
        assert!(
            blank.rgba.chunks_exact(4).all(|p| p[3] == 180),
            "alpha kept"
        );
    }
}
