//! The layers land where they belong on heads that are not the template, measured in 3D
//! against each head's landmarks (issue "any head").
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::PathBuf;

use glam::{Vec2, Vec3};

use super::*;

pub(super) fn heads_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../assets/heads")
}

fn wrinkle_file(region: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/wrinkles")
        .join(format!("{region}.wrk"))
}

/// The 3D point at each texel centre of `mesh`'s UV layout (`None` off every island).
fn uv_positions(mesh: &Mesh, size: u32) -> Vec<Option<Vec3>> {
    let n = size as usize;
    let mut out = vec![None; n * n];
    let (p, uv) = (mesh.positions(), mesh.uvs());
    for t in mesh.skin_indices().chunks_exact(3) {
        let [a, b, c] = [t[0], t[1], t[2]].map(|i| i as usize);
        crate::maps::raster::raster_uv(
            [uv[a], uv[b], uv[c]],
            size,
            0.0,
            |x, y, [w0, w1, w2], _| {
                out[y * n + x] = Some(p[a] * w0 + p[b] * w1 + p[c] * w2);
            },
        );
    }
    out
}

/// A check of a region's wrinkle points on the subject's right and left.
type SideTest<'a> = dyn Fn(&[Vec3], &[Vec3]) -> Result<(), String> + 'a;

struct Head {
    name: &'static str,
    file: &'static str,
}

const HEADS: [Head; 4] = [
    // The template itself, read at its own UVs: its layout checked against its landmarks.
    Head {
        name: "default head",
        file: "",
    },
    Head {
        name: "lee-perry-smith",
        file: "LeePerrySmith.glb",
    },
    Head {
        name: "makehuman",
        file: "mh_head.obj",
    },
    // The procedural mannequin that was the default head before the scan.
    Head {
        name: "mannequin",
        file: "mannequin.glb",
    },
];

fn reference_landmarks(head: &Head) -> crate::head::landmarks::Landmarks {
    if head.file.is_empty() {
        crate::head::fit::template().landmarks.clone()
    } else {
        crate::head::landmarks::Landmarks::load(&heads_dir().join(head.name).join("landmarks.json"))
            .unwrap()
    }
}

fn project_for(head: &Head, landmarks: bool) -> Project {
    let dir = heads_dir().join(head.name);
    let mut p = Project::default();
    p.pores.enabled = false;
    p.furrows.enabled = false;
    p.noise.strength = 0.0;
    // The wrinkles' own places: without the shape's relief, which the large map also
    // carries (crate::layers::shape::relief has its own tests).
    p.shape.enabled = false;
    if head.file.is_empty() {
        return p;
    }
    p.mesh.path = Some(dir.join(head.file));
    p.mesh.metres_per_unit = None;
    p.mesh.landmarks = landmarks.then(|| dir.join("landmarks.json").into());
    p
}

/// Where a region's wrinkles are: the 3D points of the texels at over half the map's
/// peak, split into the subject's right (x below the face's midline) and left.
fn wrinkle_points(scene: &mut Scene, size: u32) -> Vec<Vec3> {
    scene
        .bake(&BakeRequest::maps(size, 1.0, false), &CancelToken::never())
        .unwrap();
    let map = &scene.large().unwrap().height;
    let peak = map.data().iter().fold(0.0f32, |m, &h| m.max(h.abs()));
    assert!(peak > 0.0, "no wrinkle baked");
    let points = uv_positions(scene.mesh(), size);
    map.data()
        .iter()
        .zip(&points)
        .filter(|(h, p)| h.abs() > 0.5 * peak && p.is_some())
        .map(|(_, p)| p.unwrap())
        .collect()
}

fn centroid(points: &[Vec3]) -> Vec3 {
    points.iter().sum::<Vec3>() / points.len().max(1) as f32
}

#[test]
fn every_region_lands_where_it_belongs_on_heads_that_are_not_the_template() {
    let size = 512;
    for head in &HEADS {
        for with_landmarks in [true, false] {
            let mut project = project_for(head, with_landmarks);
            // The head's own landmarks (hand-placed) are the reference in both cases.
            let l = reference_landmarks(head);
            let g = |n: &str| l.get(n).unwrap();
            let eyes = l.exocanthion_distance().unwrap();
            let mid_x = (g("exocanthion_r").x + g("exocanthion_l").x) * 0.5;
            let what = format!(
                "{} ({} landmarks)",
                head.name,
                if with_landmarks {
                    "hand-placed"
                } else {
                    "automatic"
                }
            );
            let mut check = |region: &str, test: &SideTest<'_>| {
                project.large.wrinkles = vec![wrinkle_file(region)];
                let mut scene = Scene::new(project.clone()).unwrap();
                assert!(
                    scene.layout().fit.is_some() || head.file.is_empty(),
                    "{what}: {}",
                    scene.layout().how
                );
                let points = wrinkle_points(&mut scene, size);
                let (right, left): (Vec<Vec3>, Vec<Vec3>) =
                    points.iter().partition(|p| p.x < mid_x);
                if let Err(e) = test(&right, &left) {
                    panic!(
                        "{what}, {region}: {e} (right {:?}, left {:?}, {} texels)",
                        centroid(&right),
                        centroid(&left),
                        points.len()
                    );
                }
            };
            let near = |p: Vec3, q: Vec3, r: f32, what: &str| {
                if p.distance(q) <= r * eyes {
                    Ok(())
                } else {
                    Err(format!(
                        "{what}: {:.2} × the eye distance away",
                        p.distance(q) / eyes
                    ))
                }
            };
            check("forehead", &|r, l| {
                let c = centroid(&[r, l].concat());
                if c.y <= g("glabella").y {
                    return Err("not above the brows".into());
                }
                if (c.x - mid_x).abs() > 0.25 * eyes {
                    return Err("not over the middle of the forehead".into());
                }
                near(c, g("glabella"), 0.9, "the forehead lines and the glabella")
            });
            check("crows-feet", &|r, l| {
                near(centroid(r), g("exocanthion_r"), 0.35, "right crow's feet")?;
                near(centroid(l), g("exocanthion_l"), 0.35, "left crow's feet")
            });
            check("nasolabial", &|r, l| {
                for (side, pts) in [("r", r), ("l", l)] {
                    let c = centroid(pts);
                    let (wing, corner) =
                        (g(&format!("alare_{side}")), g(&format!("cheilion_{side}")));
                    let between = (wing + corner) * 0.5;
                    near(
                        c,
                        between,
                        0.3,
                        &format!("nasolabial {side} from between nose wing and mouth corner"),
                    )?;
                }
                Ok(())
            });
            check("marionette", &|r, l| {
                for (side, pts) in [("r", r), ("l", l)] {
                    let c = centroid(pts);
                    let corner = g(&format!("cheilion_{side}"));
                    if c.y >= corner.y {
                        return Err(format!("marionette {side} not below the mouth corner"));
                    }
                    near(
                        c,
                        corner,
                        0.45,
                        &format!("marionette {side} from the mouth corner"),
                    )?;
                }
                Ok(())
            });
            check("neck", &|r, l| {
                let c = centroid(&[r, l].concat());
                if c.y >= g("pogonion").y {
                    return Err("the neck lines are not below the chin".into());
                }
                Ok(())
            });
        }
    }
}

#[test]
fn no_hair_grows_on_the_face_of_heads_that_are_not_the_template() {
    for head in &HEADS {
        let mut project = project_for(head, true);
        project.large.enabled = false;
        let mut scene = Scene::new(project).unwrap();
        let mut request = BakeRequest::preview(0.0);
        request.large_size_px = 64;
        request.micro_size_px = 64;
        scene.bake(&request, &CancelToken::never()).unwrap();
        let hair = scene.hair().unwrap();
        assert!(hair.len() > 1000, "{}: {} hairs", head.name, hair.len());
        let l = match &scene.layout().landmarks {
            Some(l) => (**l).clone(),
            None => reference_landmarks(head),
        };
        let eyes = l.exocanthion_distance().unwrap();
        for name in [
            "pronasale",
            "exocanthion_r",
            "exocanthion_l",
            "cheilion_r",
            "cheilion_l",
            "pogonion",
            "subnasale",
        ] {
            let p = l.get(name).unwrap();
            let on_face = hair
                .instances()
                .iter()
                .filter(|h| h.position().distance(p) < 0.45 * eyes)
                .count();
            assert_eq!(on_face, 0, "{}: {on_face} hairs near {name}", head.name);
        }
        // And the scalp has hair: some roots above the brows, behind the forehead.
        let top = l.get("glabella").unwrap().y + 0.5 * eyes;
        assert!(
            hair.instances()
                .iter()
                .filter(|h| h.position().y > top)
                .count()
                > hair.len() / 4,
            "{}: the scalp is bald",
            head.name
        );
    }
}

/// The large-wrinkle map of a head file, baked at `size` at age 1 with the default
/// wrinkle files, landmarks found automatically.
fn default_map(path: &std::path::Path, size: u32) -> (Scene, Vec<f32>) {
    let mut p = Project::default();
    p.mesh.path = Some(path.to_owned());
    p.mesh.metres_per_unit = None;
    p.pores.enabled = false;
    p.furrows.enabled = false;
    p.noise.strength = 0.0;
    let mut scene = Scene::new(p).unwrap();
    assert!(scene.layout().fit.is_some(), "{}", scene.layout().how);
    scene
        .bake(&BakeRequest::maps(size, 1.0, false), &CancelToken::never())
        .unwrap();
    let map = scene.large().unwrap().height.data().to_vec();
    (scene, map)
}

/// The scan in metres, decimetres, centimetres and millimetres, and turned Z-up facing
/// −Y: the same maps (the units and axes found from the head alone, no landmarks; the
/// fit scale-free).
#[test]
fn copies_of_one_head_in_other_units_and_axes_give_the_same_maps() {
    let dir = tempfile::tempdir().unwrap();
    let scan = Mesh::load(&heads_dir().join("lee-perry-smith/LeePerrySmith.glb")).unwrap();
    // The scan's own unit is ≈ 0.0518 m.
    let unit = 0.0518;
    let size = 256;
    let to_z_up = glam::Mat3::from_cols(Vec3::X, Vec3::Z, Vec3::NEG_Y);
    let copies: [(&str, f32, bool); 5] = [
        ("m", unit, false),
        ("dm", unit * 10.0, false),
        ("cm", unit * 100.0, false),
        ("mm", unit * 1000.0, false),
        ("cm-z-up", unit * 100.0, true),
    ];
    let mut reference: Option<Vec<f32>> = None;
    for (name, scale, z_up) in copies {
        let path = dir.path().join(format!("scan-{name}.obj"));
        let place = |p: Vec3| {
            let p = p * scale;
            if z_up { to_z_up * p } else { p }
        };
        std::fs::write(&path, crate::head::mesh::obj::to_obj(&scan, place)).unwrap();
        // No landmarks: the Z-up copy's axes are found by fitting the template.
        let (scene, map) = default_map(&path, size);
        let axes = scene.axes();
        let want = if z_up {
            (
                crate::head::mesh::units::Axis::PosZ,
                crate::head::mesh::units::Axis::NegY,
            )
        } else {
            (
                crate::head::mesh::units::Axis::PosY,
                crate::head::mesh::units::Axis::PosZ,
            )
        };
        assert_eq!(
            (axes.up, axes.forward),
            want,
            "{name}: {}",
            scene.axes_how()
        );
        let mpu = scene.metres_per_unit();
        assert!(
            (mpu * scale / unit - 1.0).abs() < 0.03,
            "{name}: {mpu} m per unit ({})",
            scene.units().how
        );
        compare(name, &reference, &map, &scene);
        if reference.is_none() {
            reference = Some(map);
        }
    }

    fn compare(name: &str, reference: &Option<Vec<f32>>, map: &[f32], scene: &Scene) {
        let Some(r) = reference else { return };
        let peak = r.iter().fold(0.0f32, |m, h| m.max(h.abs()));
        // Texels that differ by over a tenth of the peak: the fits agree to a fraction of
        // a wrinkle's width.
        let off = r
            .iter()
            .zip(map)
            .filter(|(a, b)| (*a - *b).abs() > 0.1 * peak)
            .count();
        let wrinkled = r.iter().filter(|h| h.abs() > 0.1 * peak).count();
        assert!(
            off * 20 <= wrinkled,
            "{name}: {off} of {wrinkled} wrinkled texels differ ({})",
            scene.layout().how
        );
    }
}

/// The scan re-cut down the middle of the face: the triangles of the subject's right
/// (x < 0) get `recut(uv, true)`, the others `recut(uv, false)`; written as OBJ.
fn recut_scan(dir: &std::path::Path, name: &str, recut: impl Fn(Vec2, bool) -> Vec2) -> PathBuf {
    let scan = Mesh::load(&heads_dir().join("lee-perry-smith/LeePerrySmith.glb")).unwrap();
    let mut positions = Vec::new();
    let mut uvs = Vec::new();
    let mut indices = Vec::new();
    // Vertices shared as in the scan, split only along the cut.
    let mut copies = std::collections::HashMap::new();
    for [a, b, c] in scan.triangles() {
        let corners = [a, b, c].map(|i| i as usize);
        let right = corners.iter().all(|&i| scan.positions()[i].x < 0.0);
        for i in corners {
            let v = *copies.entry((i, right)).or_insert_with(|| {
                positions.push(scan.positions()[i]);
                uvs.push(recut(scan.uvs()[i], right));
                positions.len() as u32 - 1
            });
            indices.push(v);
        }
    }
    let raw = crate::head::mesh::RawMesh {
        positions,
        uvs: Some(uvs),
        indices,
        ..Default::default()
    };
    let recut = Mesh::build(raw, name).unwrap();
    let path = dir.join(format!("{name}.obj"));
    std::fs::write(&path, crate::head::mesh::obj::to_obj(&recut, |p| p)).unwrap();
    path
}

/// Bilinear height of `map` (`size`², v up) at `uv`.
fn sample_map(map: &[f32], size: u32, uv: Vec2) -> f32 {
    let n = size as f32;
    let (x, y) = (uv.x * n - 0.5, (1.0 - uv.y) * n - 0.5);
    let (x0, y0) = (x.floor(), y.floor());
    let at = |xi: f32, yi: f32| {
        let (xi, yi) = (xi.clamp(0.0, n - 1.0), yi.clamp(0.0, n - 1.0));
        map[yi as usize * size as usize + xi as usize]
    };
    let (fx, fy) = (x - x0, y - y0);
    let top = at(x0, y0) * (1.0 - fx) + at(x0 + 1.0, y0) * fx;
    let bottom = at(x0, y0 + 1.0) * (1.0 - fx) + at(x0 + 1.0, y0 + 1.0) * fx;
    top * (1.0 - fy) + bottom * fy
}

/// Texels on both sides of a UV seam that are one 3D point get one height: the scan's
/// face cut down the middle by `recut_scan`, baked at `size`, and the heights compared
/// along the cut (`at(uv, right)` is where the scan's `uv` lies in the baked map).
fn check_seam(path: &std::path::Path, size: u32, at: impl Fn(&Mesh, Vec2, bool) -> Vec2) {
    let scan = Mesh::load(&heads_dir().join("lee-perry-smith/LeePerrySmith.glb")).unwrap();
    let (scene, map) = default_map(path, size);
    let peak = map.iter().fold(0.0f32, |m, h| m.max(h.abs()));
    // The cut's edges: shared by a triangle moved to the right island and one kept.
    let mut edges: std::collections::HashMap<(u32, u32), [bool; 2]> = Default::default();
    for [a, b, c] in scan.triangles() {
        let right = [a, b, c]
            .iter()
            .all(|&i| scan.positions()[i as usize].x < 0.0);
        for (p, q) in [(a, b), (b, c), (c, a)] {
            edges.entry((p.min(q), p.max(q))).or_default()[usize::from(right)] = true;
        }
    }
    // Points along each seam edge, read in both islands.
    let (mut pairs, mut worst, mut wrinkled) = (0, 0.0f32, 0);
    for (&(a, b), sides) in &edges {
        if sides != &[true, true] {
            continue;
        }
        let (ua, ub) = (scan.uvs()[a as usize], scan.uvs()[b as usize]);
        for s in [0.25f32, 0.5, 0.75] {
            let uv = ua.lerp(ub, s);
            let kept = sample_map(&map, size, at(scene.mesh(), uv, false));
            let moved = sample_map(&map, size, at(scene.mesh(), uv, true));
            pairs += 1;
            worst = worst.max((kept - moved).abs());
            wrinkled += usize::from(kept.abs().max(moved.abs()) > 0.05 * peak);
        }
    }
    eprintln!(
        "{}: {pairs} points on the seam ({wrinkled} on a wrinkle), worst difference {worst} (peak {peak})",
        path.display()
    );
    assert!(pairs > 40, "only {pairs} points on the seam");
    // The seam runs down the middle of the forehead, through its middle lines.
    assert!(wrinkled >= 5, "only {wrinkled} seam points on a wrinkle");
    // The creases are narrow (a quarter of their spacing): a bilinear read a fraction of
    // a texel off on one side differs by a few % of the peak; a side reading another part
    // of the template would differ by the peak.
    assert!(
        worst <= 0.15 * peak,
        "heights across the seam differ by up to {worst} (peak {peak}, {pairs} pairs)"
    );
}

/// The scan re-cut into islands: the chart shrunk into the left half of the square, the
/// triangles of the subject's right moved by +0.5 in u into the right half.
#[test]
fn heights_agree_across_a_uv_seam() {
    let dir = tempfile::tempdir().unwrap();
    let half = |uv: Vec2, right: bool| Vec2::new(uv.x * 0.5 + if right { 0.5 } else { 0.0 }, uv.y);
    let path = recut_scan(dir.path(), "islands", half);
    check_seam(&path, 512, |_, uv, right| half(uv, right));
}

/// The scan made a two-tile UDIM head (the subject's right moved to tile 1002): it is
/// baked tile by tile in its atlas, each tile's texels as the single-tile scan's, and
/// heights agree across the tile border.
#[test]
fn a_udim_head_is_baked_tile_by_tile() {
    let dir = tempfile::tempdir().unwrap();
    let tiles = |uv: Vec2, right: bool| uv + Vec2::new(if right { 1.0 } else { 0.0 }, 0.0);
    let path = recut_scan(dir.path(), "udim", tiles);
    let head = Mesh::load(&path).unwrap();
    let udim = head.udim().expect("two tiles found");
    assert_eq!(udim.numbers(), [1001, 1002]);
    assert_eq!(udim.grid(), 2);
    let back = head.file_uvs();
    let scan = Mesh::load(&heads_dir().join("lee-perry-smith/LeePerrySmith.glb")).unwrap();
    assert!(
        back.iter()
            .all(|uv| (uv.x < 1.0 && uv.x >= 0.0) || (1.0..=2.0).contains(&uv.x)),
        "the file's UVs come back"
    );
    assert_eq!(head.triangle_count(), scan.triangle_count());

    // The atlas is the layout the bake sees: the same head laid out in one tile as the
    // atlas lays it out (the tiles side by side, half size) bakes the same texels.
    let size = 512u32;
    let atlas_layout = |uv: Vec2, right: bool| {
        (uv + Vec2::new(if right { 1.0 } else { 0.0 }, 0.0)) / udim.grid() as f32
    };
    let one_tile = recut_scan(dir.path(), "one-tile", atlas_layout);
    let (_, atlas) = default_map(&path, size);
    let (_, single) = default_map(&one_tile, size);
    let peak = single.iter().fold(0.0f32, |m, h| m.max(h.abs()));
    let off = atlas
        .iter()
        .zip(&single)
        .filter(|(a, b)| (*a - *b).abs() > 1e-3 * peak)
        .count();
    eprintln!(
        "{off} of {} texels differ by over 0.1 % of the peak {peak}",
        atlas.len()
    );
    assert!(off * 1000 <= atlas.len(), "{off} texels differ");
    // Each tile is its cell of the atlas.
    let tile = udim.crop(1, &atlas, size, 1);
    assert_eq!(tile.len(), (size as usize / 2).pow(2));
    assert_eq!(
        tile[0],
        atlas[(size as usize / 2) * size as usize + size as usize / 2]
    );

    check_seam(&path, 512, |mesh, uv, right| {
        mesh.udim()
            .unwrap()
            .to_atlas(usize::from(right), tiles(uv, right))
    });

    // Its colour map, one picture per tile, is read into the atlas; a missing tile is an
    // error naming its file.
    let textured = dir.path().join("textured.obj");
    let obj = std::fs::read_to_string(&path).unwrap();
    std::fs::write(&textured, format!("mtllib skin.mtl\n{obj}")).unwrap();
    std::fs::write(
        dir.path().join("skin.mtl"),
        "newmtl skin\nmap_Kd skin.1001.png\n",
    )
    .unwrap();
    for (n, rgb) in [(1001, [200, 30, 30]), (1002, [30, 30, 200])] {
        image::RgbImage::from_pixel(8, 8, image::Rgb(rgb))
            .save(dir.path().join(format!("skin.{n}.png")))
            .unwrap();
    }
    let mut p = Project::default();
    p.mesh.path = Some(textured.clone());
    let scene = Scene::new(p.clone()).unwrap();
    let colour = scene.colour_map().expect("the tiles read");
    assert_eq!((colour.width_px, colour.height_px), (16, 16));
    let at = |x: usize, y: usize| &colour.rgba[(y * 16 + x) * 4..(y * 16 + x) * 4 + 3];
    assert_eq!(at(2, 12), [200, 30, 30], "tile 1001 bottom left");
    assert_eq!(at(12, 12), [30, 30, 200], "tile 1002 bottom right");
    assert_eq!(scene.file_texture_paths().len(), 2);
    std::fs::remove_file(dir.path().join("skin.1002.png")).unwrap();
    let err = Scene::new(p).unwrap_err().to_string();
    assert!(err.contains("skin.1002.png"), "{err}");
}

/// `mesh.skin_parts` chooses the skin by hand: the MakeHuman head's eyes are left out by
/// their names, taken in when named; a name that matches no part is an error naming it
/// and the parts there are.
#[test]
fn the_skin_parts_can_be_chosen_by_hand() {
    let mut p = project_for(&HEADS[2], true);
    let by_name = Scene::new(p.clone()).unwrap();
    let all = by_name.mesh().indices().len();
    let skin = by_name.mesh().skin_indices().len();
    assert!(skin < all, "the eyes are not skin by their names");
    p.mesh.skin_parts = Some(vec!["head".into(), "EYE".into()]);
    let chosen = Scene::new(p.clone()).unwrap();
    assert_eq!(chosen.mesh().skin_indices().len(), all);
    p.mesh.skin_parts = Some(vec!["head".into(), "torso".into()]);
    let e = Scene::new(p).unwrap_err().to_string();
    assert!(
        e.contains("mesh.skin_parts") && e.contains("torso") && e.contains("eye_l"),
        "{e}"
    );
}

/// A head file's own pictures are kept: a GLB whose material embeds a base colour and a
/// normal map, and an OBJ whose material library names them, give the scene those maps
/// without the project naming any; the project's own pictures win over them.
#[test]
fn a_head_files_own_textures_are_read_from_its_material() {
    let dir = tempfile::tempdir().unwrap();
    let png = |rgb: [u8; 3]| {
        let mut bytes = Vec::new();
        image::RgbImage::from_pixel(4, 2, image::Rgb(rgb))
            .write_to(
                &mut std::io::Cursor::new(&mut bytes),
                image::ImageFormat::Png,
            )
            .unwrap();
        bytes
    };
    let (colour, normal) = (png([200, 120, 90]), png([140, 128, 250]));
    let head = crate::head::default::default_head();
    let material = crate::head::mesh::gltf::GlbMaterial {
        name: "skin".into(),
        base_colour: [1.0; 4],
        base_colour_png: Some(colour.clone()),
        roughness: 0.5,
        metallic: 0.0,
        normal_png: Some(normal.clone()),
        orm_png: None,
        extras: serde_json::Value::Null,
    };
    let glb = dir.path().join("textured.glb");
    std::fs::write(
        &glb,
        crate::head::mesh::gltf::write_glb_with_material(&head, Some(&material)),
    )
    .unwrap();
    // The OBJ: its mtllib names the pictures beside it.
    let obj = dir.path().join("textured.obj");
    let text = format!(
        "mtllib textured.mtl\nusemtl skin\n{}",
        crate::head::mesh::obj::to_obj(&head, |p| p)
    );
    std::fs::write(&obj, text).unwrap();
    std::fs::write(
        dir.path().join("textured.mtl"),
        "newmtl skin\nKd 1 1 1\nmap_Kd -bm 1 colour.png\nnorm normal.png\n",
    )
    .unwrap();
    std::fs::write(dir.path().join("colour.png"), &colour).unwrap();
    std::fs::write(dir.path().join("normal.png"), &normal).unwrap();
    for path in [glb, obj] {
        let mut p = Project::default();
        p.mesh.path = Some(path.clone());
        p.mesh.layout = crate::project::Layout::OwnUvs;
        let scene = Scene::new(p.clone()).unwrap();
        let c = scene.colour_map().expect("the file's colour map");
        assert_eq!((c.width_px, c.height_px), (4, 2));
        assert_eq!(&c.rgba[..4], &[200, 120, 90, 255], "{}", path.display());
        let n = scene.normal_map().expect("the file's normal map");
        assert_eq!(&n.rgba[..3], &[140, 128, 250]);
        assert_eq!(
            scene.file_textures().len(),
            2,
            "{:?}",
            scene.file_textures()
        );
        // The OBJ's pictures are files beside it, read with the mesh: one changed on disk
        // is read again with a new version of the mesh file (the editor watches them).
        let is_obj = path.extension().is_some_and(|e| e == "obj");
        let files = scene.file_texture_paths().to_vec();
        if is_obj {
            assert_eq!(
                files,
                [dir.path().join("colour.png"), dir.path().join("normal.png")]
            );
            let mut scene = scene;
            std::fs::write(dir.path().join("colour.png"), png([10, 20, 30])).unwrap();
            scene
                .set_file_versions(&FileVersions::from([(path.clone(), 1)]))
                .unwrap();
            assert_eq!(&scene.colour_map().unwrap().rgba[..3], &[10, 20, 30]);
            std::fs::write(dir.path().join("colour.png"), &colour).unwrap();
        } else {
            assert!(files.is_empty(), "embedded: {files:?}");
        }
        // The project's own picture wins.
        p.mesh.colour_map = Some(dir.path().join("normal.png"));
        let scene = Scene::new(p).unwrap();
        assert_eq!(&scene.colour_map().unwrap().rgba[..3], &[140, 128, 250]);
    }
    // A material naming a picture outside the head's folder is refused, naming it.
    let bad = dir.path().join("bad.obj");
    std::fs::write(&bad, "mtllib bad.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    std::fs::write(
        dir.path().join("bad.mtl"),
        "newmtl m\nmap_Kd ../../etc/x.png\n",
    )
    .unwrap();
    let mut p = Project::default();
    p.mesh.path = Some(bad);
    let e = Scene::new(p).unwrap_err().to_string();
    assert!(e.contains("map_Kd") && e.contains("etc/x.png"), "{e}");
}

/// `mesh.landmarks` holding the points themselves fits the head as its landmark file does
/// (the same units, the same baked map); a point of an unknown name is refused, named.
#[test]
fn landmarks_written_in_the_project_fit_as_their_file_does() {
    let head = &HEADS[2];
    let from_file = project_for(head, true);
    let file = reference_landmarks(head);
    let mut inline = from_file.clone();
    let points: std::collections::BTreeMap<String, [f32; 3]> = crate::head::landmarks::NAMES
        .iter()
        .filter_map(|n| Some(((*n).to_owned(), file.get(n)?.to_array())))
        .collect();
    inline.mesh.landmarks = Some(crate::project::LandmarkSource::Points(points.clone()));
    // Through the project file's text too: the points are written and read back.
    let text = inline.to_json_pretty();
    let inline = Project::from_json_str(&text, "inline.agesim.json").unwrap();
    assert!(inline.mesh.landmark_file().is_none());
    let request = BakeRequest::maps(128, 1.0, false);
    let bake = |p: Project| {
        let mut s = Scene::new(p).unwrap();
        s.bake(&request, &CancelToken::never()).unwrap();
        (
            s.units().metres_per_unit,
            s.large().unwrap().height.data().to_vec(),
        )
    };
    assert_eq!(bake(inline), bake(from_file));
    // An unknown name: an error naming the field and the point.
    let bad = text.replacen("\"pronasale\"", "\"nose_tip\"", 1);
    let e = Project::from_json_str(&bad, "bad.agesim.json")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("mesh.landmarks") && e.contains("nose_tip"),
        "{e}"
    );
}

/// The crow's feet are laid on the surface through each head's own layout: a second head
/// read at its own UVs gets its own warps, not the last head's (they are kept per mesh),
/// so its map is the one a fresh scene bakes for it, byte for byte; and a head whose
/// layout is squeezed toward the middle has another map.
#[test]
fn each_head_read_at_its_own_uvs_has_its_own_surface_warps() {
    let dir = tempfile::tempdir().unwrap();
    let squeezed = recut_scan(dir.path(), "squeezed", |uv, _| uv * 0.9 + Vec2::splat(0.05));
    let scan = recut_scan(dir.path(), "scan", |uv, _| uv);
    let project = |path: &std::path::Path| {
        let mut p = Project::default();
        p.mesh.path = Some(path.to_owned());
        p.mesh.layout = crate::project::Layout::OwnUvs;
        p.pores.enabled = false;
        p.furrows.enabled = false;
        p.noise.strength = 0.0;
        p
    };
    let request = BakeRequest::maps(256, 1.0, false);
    let never = CancelToken::never();
    let map = |scene: &Scene| scene.large().unwrap().height.data().to_vec();
    let mut fresh = Scene::new(project(&scan)).unwrap();
    fresh.bake(&request, &never).unwrap();
    let mut scene = Scene::new(project(&squeezed)).unwrap();
    scene.bake(&request, &never).unwrap();
    let first = map(&scene);
    scene.set_project(project(&scan)).unwrap();
    scene.bake(&request, &never).unwrap();
    assert!(
        map(&scene) == map(&fresh),
        "the second head's map is a fresh scene's"
    );
    assert!(first != map(&fresh), "the squeezed layout has another map");
}

/// A head's points as the shape reads them follow its skin without folding: over the
/// cheeks, no triangle of a panel head turns over on the template's face frame. (The
/// shape once read each skin point's closest point on the template, which leapt across
/// the template's deep nasolabial creases: strips of folded triangles along both folds,
/// where the cheek's roll then drew a crack. The refined points are a smooth field's.)
#[test]
fn a_head_s_shape_points_do_not_fold_over_the_cheeks() {
    let mut p = Project::default();
    p.mesh.path = Some(heads_dir().join("panel/caucasian-female.obj"));
    p.mesh.metres_per_unit = None;
    let scene = Scene::new(p).unwrap();
    let frame = crate::head::frame::Regions::template().unwrap();
    let points = scene.shape_points();
    let mesh = scene.mesh();
    let (mut cheek, mut folded) = (0, 0);
    for t in mesh.skin_indices().chunks_exact(3) {
        let v = [0, 1, 2].map(|k| t[k] as usize);
        let Some(q) = v
            .iter()
            .map(|&i| points[i].map(|p| frame.relative(p)))
            .collect::<Option<Vec<_>>>()
        else {
            continue;
        };
        let on_cheek = |q: &Vec3| (0.3..1.0).contains(&q.x.abs()) && (-1.4..-0.5).contains(&q.y);
        if !q.iter().all(on_cheek) || q.iter().any(|q| q.z < 0.1) {
            continue;
        }
        let p = v.map(|i| mesh.positions()[i]);
        let area = |a: Vec2, b: Vec2, c: Vec2| (b - a).perp_dot(c - a);
        let on_frame = area(q[0].truncate(), q[1].truncate(), q[2].truncate());
        let on_head = area(p[0].truncate(), p[1].truncate(), p[2].truncate());
        cheek += 1;
        folded += usize::from(on_frame * on_head < 0.0);
    }
    eprintln!("{folded} of {cheek} cheek triangles folded on the frame");
    assert!(cheek > 300, "{cheek}");
    assert!(folded * 100 <= cheek, "{folded} of {cheek}");
}
