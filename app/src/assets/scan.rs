//! The default head, converted from the Lee Perry-Smith scan in `assets/heads/lee-perry-smith/`
//! ("Infinite, 3D Head Scan by Lee Perry-Smith, licensed under CC BY 3.0, based on a work at
//! triplegangers.com"). `agesim gen-assets` writes the result to
//! `assets/meshes/default-head.glb` (with the scan's colour map, its ears corrected, and
//! normal map embedded) and `assets/meshes/default-head.landmarks.json`; the engine reads those
//! (`agesim_core::head::default`), never this.
//!
//! What the conversion does to the scan, and nothing more:
//! - **frame**: metres at 95 mm between the outer eye corners (docs/models.md §7a), +Y up,
//!   the face toward +Z, the subject's left on +X; x = 0 is the face's midline (the mean of
//!   the midpoints of its left/right landmark pairs), y = 0 the outer eye corners' height,
//!   z = 0 the left ear's tragion. The rotation turns the line through the paired landmarks
//!   onto +X and keeps the scan's own up as near +Y as that allows (the scan is turned ≈ 3°);
//! - **shoulders cut**: the scan (down to the chest) is clipped by the plane
//!   [`NECK_BELOW_EYES_M`] below the eyes, triangles across it cut at the plane, so views
//!   and the fit are the head's and the neck ends in a straight edge;
//! - **eye sockets**: the patches inside the closed lids (the two discs in the chart's top
//!   corners) become a part of their own, which is not skin (docs/models.md §7a);
//! - **UVs**: the scan's UVs are in OBJ's convention relative to its maps, so the glTF v flip
//!   is undone (`v ↦ 1 − v`) and the maps are used as they are;
//! - **landmarks**: the hand-placed points of `landmarks.json` moved into the new frame, with
//!   the right tragion (missing: the scan's right ear is half hidden) the left one mirrored,
//!   each then moved to the nearest point of the surface;
//! - tangents: MikkTSpace on the converted UVs, the frame the maps are sampled in;
//! - **ears**: the colour map's yellow-orange cast in the ears' bowls taken out
//!   ([`neutralise_ears`]); the rest of the map is the scan's, re-encoded.

use std::path::Path;

use agesim_core::Error;
use agesim_core::head::landmarks::Landmarks;
use agesim_core::head::mesh::{Mesh, MeshPart, RawMesh, gltf};
use anyhow::Context as _;
use glam::{Mat3, Vec2, Vec3};

/// The scan's folder, relative to the assets folder.
pub const SCAN_DIR: &str = "heads/lee-perry-smith";
/// How far below the outer eye corners the neck is cut, metres (the chin is ≈ 0.08 m below
/// them, the neck ≈ 0.1 m long).
pub const NECK_BELOW_EYES_M: f32 = 0.18;

/// How far (UV) from the chart's top corners the eye-socket patches reach.
const SOCKET_PATCH_UV: f32 = 0.08;

/// The converted scan: the default head and what comes with it.
pub struct DefaultHead {
    pub mesh: Mesh,
    /// Its landmarks, metres, in its frame.
    pub landmarks: Landmarks,
    /// The scan's colour map (JPEG), its ears' cast taken out.
    pub colour_jpeg: Vec<u8>,
    /// The scan's tangent-space normal map (JPEG, as shipped).
    pub normal_jpeg: Vec<u8>,
}

/// The bilateral landmark pairs, right then left.
const PAIRS: [(&str, &str); 4] = [
    ("exocanthion_r", "exocanthion_l"),
    ("endocanthion_r", "endocanthion_l"),
    ("alare_r", "alare_l"),
    ("cheilion_r", "cheilion_l"),
];

/// The triangles of `indices` clipped to y ≥ `y0`: those wholly below dropped, those across
/// the plane cut along it (Sutherland–Hodgman, a fan of the kept polygon). A vertex made on
/// an edge is shared by both triangles of that edge; its position, UV and normal are
/// interpolated and appended to the arrays.
fn clip_below(
    indices: &[u32],
    y0: f32,
    positions: &mut Vec<Vec3>,
    uvs: &mut Vec<Vec2>,
    mut normals: Option<&mut Vec<Vec3>>,
) -> Vec<u32> {
    let mut out = Vec::with_capacity(indices.len());
    let mut on_edge: std::collections::HashMap<(u32, u32), u32> = Default::default();
    for t in indices.chunks_exact(3) {
        let above = [t[0], t[1], t[2]].map(|i| positions[i as usize].y >= y0);
        if above.iter().all(|&a| a) {
            out.extend_from_slice(t);
            continue;
        }
        if !above.iter().any(|&a| a) {
            continue;
        }
        let mut polygon = Vec::with_capacity(4);
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            if above[k] {
                polygon.push(a);
            }
            if above[k] != above[(k + 1) % 3] {
                let key = (a.min(b), a.max(b));
                let v = *on_edge.entry(key).or_insert_with(|| {
                    let (pa, pb) = (positions[key.0 as usize], positions[key.1 as usize]);
                    let s = ((y0 - pa.y) / (pb.y - pa.y)).clamp(0.0, 1.0);
                    positions.push(pa.lerp(pb, s));
                    let uv = uvs[key.0 as usize].lerp(uvs[key.1 as usize], s);
                    uvs.push(uv);
                    if let Some(n) = normals.as_deref_mut() {
                        let m = n[key.0 as usize]
                            .lerp(n[key.1 as usize], s)
                            .normalize_or_zero();
                        n.push(m);
                    }
                    (positions.len() - 1) as u32
                });
                polygon.push(v);
            }
        }
        for k in 1..polygon.len().saturating_sub(1) {
            out.extend_from_slice(&[polygon[0], polygon[k], polygon[k + 1]]);
        }
    }
    out
}

/// Converts the scan in `assets/`[`SCAN_DIR`] (see the module docs).
pub fn convert_scan(assets: &Path) -> anyhow::Result<DefaultHead> {
    let dir = assets.join(SCAN_DIR);
    let glb = dir.join("LeePerrySmith.glb");
    let raw = gltf::load(&glb)?;
    let scan_landmarks = Landmarks::load(&dir.join("landmarks.json"))?;
    let get = |name: &str| {
        scan_landmarks
            .get(name)
            .with_context(|| format!("{}: no {name}", dir.join("landmarks.json").display()))
    };

    // Scale: 95 mm between the outer eye corners.
    let eye_span = get("exocanthion_r")?.distance(get("exocanthion_l")?);
    let scale = agesim_core::head::landmarks::EXOCANTHION_DISTANCE_M / eye_span;
    // Rotation: the pairs' right → left direction onto +X, the scan's up kept near +Y.
    let mut across = Vec3::ZERO;
    let mut mid = Vec3::ZERO;
    for (r, l) in PAIRS {
        across += get(l)? - get(r)?;
        mid += 0.5 * (get(l)? + get(r)?);
    }
    let x = across.normalize();
    let mid = mid / PAIRS.len() as f32;
    let y = (Vec3::Y - x * x.dot(Vec3::Y)).normalize();
    let z = x.cross(y);
    // Rows are the new axes: R p gives the coordinates along x, y, z.
    let rotation = Mat3::from_cols(x, y, z).transpose();
    let eyes: Vec3 = 0.5 * (get("exocanthion_r")? + get("exocanthion_l")?);
    let ear: Vec3 = get("tragion_l")?;
    let origin = Vec3::new((rotation * mid).x, (rotation * eyes).y, (rotation * ear).z);
    let to_head = |p: Vec3| (rotation * p - origin) * scale;

    let mut landmarks = Landmarks::default();
    for name in agesim_core::head::landmarks::NAMES {
        if let Some(p) = scan_landmarks.get(name) {
            landmarks.set(name, to_head(p))?;
        }
    }
    if landmarks.get("tragion_r").is_none()
        && let Some(l) = landmarks.get("tragion_l")
    {
        landmarks.set("tragion_r", Vec3::new(-l.x, l.y, l.z))?;
    }

    let RawMesh {
        positions,
        normals,
        uvs,
        indices,
        parts,
        warnings,
        ..
    } = raw;
    let mut positions: Vec<Vec3> = positions.into_iter().map(to_head).collect();
    let mut uvs: Vec<Vec2> = uvs
        .with_context(|| format!("{}: the scan has no UVs", glb.display()))?
        .into_iter()
        .map(|uv| Vec2::new(uv.x, 1.0 - uv.y))
        .collect();
    let mut normals = normals;
    // Cut the shoulders off along the plane y = −cut: triangles below it dropped, those
    // across it clipped, so the neck ends in a clean edge, not a ragged one.
    let indices = clip_below(
        &indices,
        -NECK_BELOW_EYES_M,
        &mut positions,
        &mut uvs,
        normals.as_mut(),
    );
    // The insides of the eye sockets behind the closed lids are two small patches in the
    // top corners of the chart, joined to the lids by triangles without UV area: not skin
    // (no wrinkles, no hair), a part of their own.
    // The back of the scalp reaches those corners too: a socket lies in front of the ears.
    let in_socket = |i: u32| {
        let uv = uvs[i as usize];
        let corner = uv.y > 1.0 - SOCKET_PATCH_UV
            && (uv.x < SOCKET_PATCH_UV || uv.x > 1.0 - SOCKET_PATCH_UV);
        corner && positions[i as usize].z > 0.0
    };
    let mut skin = Vec::with_capacity(indices.len());
    let mut sockets = Vec::new();
    for t in indices.chunks_exact(3) {
        if t.iter().any(|&i| in_socket(i)) {
            sockets.extend_from_slice(t);
        } else {
            skin.extend_from_slice(t);
        }
    }
    drop(parts);
    let kept_parts = vec![
        MeshPart {
            name: "skin (Lee Perry-Smith scan)".to_owned(),
            first_triangle: 0,
            triangle_count: (skin.len() / 3) as u32,
        },
        MeshPart {
            name: "eye sockets (inside the closed lids)".to_owned(),
            first_triangle: (skin.len() / 3) as u32,
            triangle_count: (sockets.len() / 3) as u32,
        },
    ];
    let mut kept_indices = skin;
    kept_indices.extend_from_slice(&sockets);
    let raw = RawMesh {
        positions,
        // The scan's own normals, turned (the rotation is orthonormal, the scale uniform).
        normals: normals.map(|n| n.into_iter().map(|n| rotation * n).collect()),
        uvs: Some(uvs),
        tangents: None,
        indices: kept_indices,
        parts: kept_parts,
        warnings,
    };
    let mesh = Mesh::build(raw, "default head (converted scan)")?;
    // The landmarks on the surface (picked by hand, a few mm off; the mirrored tragion
    // wherever the right ear is).
    let bvh = agesim_core::head::fit::bvh::Bvh::new(mesh.positions(), &mesh.skin_indices());
    let mut on_surface = Landmarks::default();
    for name in agesim_core::head::landmarks::NAMES {
        if let Some(p) = landmarks.get(name) {
            let hit = bvh
                .closest(p, f32::INFINITY)
                .with_context(|| format!("no surface near {name}"))?;
            on_surface.set(name, hit.point)?;
        }
    }
    let landmarks = on_surface;
    let read = |name: &str| -> Result<Vec<u8>, Error> {
        agesim_core::base::limits::read_file(
            &dir.join(name),
            agesim_core::base::limits::MAX_IMAGE_FILE_BYTES,
        )
    };
    let colour_jpeg = neutralise_ears(&read("Map-COL.jpg")?, &mesh, &landmarks)?;
    Ok(DefaultHead {
        mesh,
        landmarks,
        colour_jpeg,
        normal_jpeg: read("Infinite-Level_02_Tangent_SmoothUV.jpg")?,
    })
}

/// Where the ear's bowl lies from its tragion (metres, the head's frame): behind it and a
/// little below, and the radii of the ellipsoid round it that takes the correction.
const EAR_FROM_TRAGION_M: Vec3 = Vec3::new(0.0, -0.005, -0.015);
const EAR_RADII_M: Vec3 = Vec3::new(0.03, 0.035, 0.025);

/// The scan's colour map with its ears' ochre cast taken out: the scan's conchae are
/// yellow-orange (sRGB ≈ (186, 135, 105) against the skin round the ear's (195, 150,
/// 135)), which read, blind, as "a different material" on the head. Within an ellipsoid
/// round each ear ([`EAR_FROM_TRAGION_M`], [`EAR_RADII_M`], fading over its outer fifth),
/// each texel's green and blue, relative to its red, move to the skin's round the ear (the
/// mean over 45–70 mm from the ear's centre); its red, and so its light, stays. Re-encoded as
/// JPEG at quality 95.
fn neutralise_ears(jpeg: &[u8], mesh: &Mesh, landmarks: &Landmarks) -> anyhow::Result<Vec<u8>> {
    let mut image = image::load_from_memory(jpeg)
        .context("cannot decode the scan's colour map")?
        .to_rgb8();
    let (w, h) = image.dimensions();
    anyhow::ensure!(w == h, "the scan's colour map is {w}×{h}, not square");
    let surface = crate::assets::masks::Surface::new(mesh, w)?;
    let ears: Vec<Vec3> = ["tragion_l", "tragion_r"]
        .iter()
        .filter_map(|n| landmarks.get(n))
        .map(|t| t + EAR_FROM_TRAGION_M)
        .collect();
    let ellipsoid = |p: Vec3| {
        ears.iter()
            .map(|&c| ((p - c) / EAR_RADII_M).length())
            .fold(f32::INFINITY, f32::min)
    };
    let ratios = |px: &image::Rgb<u8>| {
        let [r, g, b] = px.0.map(|v| f32::from(v).max(1.0));
        Vec2::new(g / r, b / r)
    };
    let (mut sum, mut count) = (Vec2::ZERO, 0u32);
    for (k, px) in image.pixels().enumerate() {
        let p = surface.points[k];
        let d = ears
            .iter()
            .map(|c| p.distance(*c))
            .fold(f32::INFINITY, f32::min);
        if (0.045..0.07).contains(&d) && ellipsoid(p) > 1.0 {
            sum += ratios(px);
            count += 1;
        }
    }
    anyhow::ensure!(count > 0, "no skin found round the scan's ears");
    let skin = sum / count as f32;
    for (k, px) in image.pixels_mut().enumerate() {
        let weight = 1.0 - smooth01((ellipsoid(surface.points[k]) - 0.8) / 0.2);
        if weight <= 0.0 {
            continue;
        }
        let now = ratios(px);
        let to = now + (skin - now) * weight;
        let r = f32::from(px.0[0]);
        px.0[1] = (r * to.x).round().clamp(0.0, 255.0) as u8;
        px.0[2] = (r * to.y).round().clamp(0.0, 255.0) as u8;
    }
    let mut out = Vec::new();
    image::codecs::jpeg::JpegEncoder::new_with_quality(&mut out, 95)
        .encode_image(&image)
        .context("cannot encode the corrected colour map")?;
    Ok(out)
}

fn smooth01(x: f32) -> f32 {
    let t = x.clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    fn assets() -> std::path::PathBuf {
        std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../assets")
    }

    /// Angle between two directions, radians (robust near 0).
    fn angle(a: Vec3, b: Vec3) -> f32 {
        a.cross(b).length().atan2(a.dot(b))
    }

    #[test]
    fn the_shipped_head_file_matches_a_fresh_conversion() {
        // Guards assets/meshes/default-head.glb and its landmarks against going stale:
        // rerun `cargo run -p agesim -- gen-assets --out assets` when this fails.
        let fresh = convert_scan(&assets()).unwrap();
        let shipped = agesim_core::head::default::shipped_default_head().unwrap();
        // The file gives each part its own vertices (the rim between the skin and the eye
        // sockets is doubled): compared corner by corner.
        assert_eq!(
            shipped.triangle_count(),
            fresh.mesh.triangle_count(),
            "triangles"
        );
        assert_eq!(shipped.parts().len(), 2, "skin and eye sockets");
        let mut worst = [0.0f32; 4];
        for (s3, f3) in shipped.triangles().zip(fresh.mesh.triangles()) {
            for (s, f) in s3
                .into_iter()
                .zip(f3)
                .map(|(s, f)| (s as usize, f as usize))
            {
                let (ts, tf) = (shipped.tangents()[s], fresh.mesh.tangents()[f]);
                assert_eq!(ts.w, tf.w, "handedness of vertex {f}");
                let d = [
                    (shipped.positions()[s] - fresh.mesh.positions()[f]).length(),
                    (shipped.uvs()[s] - fresh.mesh.uvs()[f]).length(),
                    angle(shipped.normals()[s], fresh.mesh.normals()[f]),
                    angle(ts.truncate(), tf.truncate()),
                ];
                for (w, d) in worst.iter_mut().zip(d) {
                    *w = w.max(d);
                }
            }
        }
        let [pos_m, uv, normal_rad, tangent_rad] = worst;
        assert!(pos_m <= 1e-6, "positions differ by {pos_m} m");
        assert!(uv <= 1e-6, "UVs differ by {uv}");
        assert!(normal_rad <= 1e-5, "normals differ by {normal_rad} rad");
        assert!(tangent_rad <= 1e-5, "tangents differ by {tangent_rad} rad");
        assert_eq!(
            agesim_core::head::fit::template().landmarks,
            fresh.landmarks,
            "the template's landmarks"
        );
        // The maps are the scan's files, byte for byte.
        let textures = agesim_core::head::default::default_head_textures();
        let colour = textures.colour.as_ref().expect("a colour map");
        assert_eq!((colour.width_px, colour.height_px), (1024, 1024));
        assert!(textures.normal.is_some(), "a normal map");
    }

    #[test]
    fn the_conversion_puts_the_head_in_metres_upright_facing_z() {
        let head = convert_scan(&assets()).unwrap();
        let l = &head.landmarks;
        let g = |n: &str| l.get(n).unwrap();
        // 95 mm between the outer eye corners; the eyes at y = 0, level.
        assert!((l.exocanthion_distance().unwrap() - 0.095).abs() < 1e-3);
        assert!((g("exocanthion_r").y - g("exocanthion_l").y).abs() < 0.003);
        // Up: the crown above the eyes above the chin; the nose in front (+Z).
        assert!(g("vertex").y > 0.1 && g("pogonion").y < -0.09);
        assert!(g("pronasale").z > g("tragion_l").z + 0.09);
        // The subject's left on +X; the right tragion mirrored from the left one.
        assert!(g("exocanthion_l").x > 0.04 && g("exocanthion_r").x < -0.04);
        // (The right ear is nearer the midline than the left: 7 mm.)
        assert!((g("tragion_r").x + g("tragion_l").x).abs() < 0.01);
        // The shoulders cut off below the neck, along the plane (a straight edge).
        let bottom = head.mesh.bounds().min.y;
        assert!((bottom + NECK_BELOW_EYES_M).abs() < 1e-5, "{bottom}");
    }
}
