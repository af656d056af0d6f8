//! Fitting the template to a head (issue "any head": ≤ 2 s for a 50k-triangle head) and
//! the correspondence map at 4096² (≤ 1 s).
//!
//! Heads: the Lee Perry-Smith scan (17 684 triangles) and the scan subdivided once
//! (every triangle into four: 70 736 triangles, over the 50k of the budget). Measured:
//! the automatic landmarks, the fit from landmarks, and the correspondence map.
//! Baselines in the same run: the fit's closest points by a scan of every template
//! triangle (for 64 vertices, scaled to the head), and writing a 4096² map of template
//! UVs with no work per texel (the memory floor of the correspondence map).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use agesim_core::Mesh;
use agesim_core::base::cancel::CancelToken;
use agesim_core::head::fit::{self, Correspondence};
use agesim_core::head::landmarks::Landmarks;
use agesim_core::head::mesh::RawMesh;
use glam::{Vec2, Vec3};

mod common;
use common::{ms, time};

/// Every triangle into four (corners and edge midpoints, unshared).
fn subdivided(m: &Mesh) -> Mesh {
    let (p, uv) = (m.positions(), m.uvs());
    let mut raw = RawMesh {
        uvs: Some(Vec::new()),
        ..RawMesh::default()
    };
    for [a, b, c] in m.triangles() {
        let v: [(Vec3, Vec2); 3] = [a, b, c].map(|i| (p[i as usize], uv[i as usize]));
        let mid = |i: usize, j: usize| ((v[i].0 + v[j].0) * 0.5, (v[i].1 + v[j].1) * 0.5);
        let (ab, bc, ca) = (mid(0, 1), mid(1, 2), mid(2, 0));
        for tri in [[v[0], ab, ca], [ab, v[1], bc], [ca, bc, v[2]], [ab, bc, ca]] {
            for (q, t) in tri {
                raw.indices.push(raw.positions.len() as u32);
                raw.positions.push(q);
                raw.uvs.as_mut().unwrap().push(t);
            }
        }
    }
    Mesh::build(raw, "scan subdivided").unwrap()
}

fn main() {
    let dir = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../assets/heads/lee-perry-smith"
    );
    let scan = Mesh::load(std::path::Path::new(&format!("{dir}/LeePerrySmith.glb"))).unwrap();
    let hand = Landmarks::load(std::path::Path::new(&format!("{dir}/landmarks.json"))).unwrap();
    let template = fit::template();
    let never = CancelToken::never();
    println!("threads: {}", rayon::current_num_threads());
    for head in [scan.clone(), subdivided(&scan)] {
        let tris = head.triangle_count();
        let auto = time(3, || {
            std::hint::black_box(fit::auto::landmarks(&head, template, 0.05).unwrap());
        });
        let fitted = time(5, || {
            std::hint::black_box(fit::fit(&head, &hand, template).unwrap());
        });
        let f = fit::fit(&head, &hand, template).unwrap();
        let corr = time(3, || {
            std::hint::black_box(Correspondence::new(&head, &f, 4096, &never).unwrap());
        });
        // Baseline: closest points by scanning every template triangle.
        let tp = template.mesh.positions();
        let tri: Vec<[Vec3; 3]> = template
            .mesh
            .triangles()
            .map(|t| t.map(|i| tp[i as usize]))
            .collect();
        let sample = 64;
        let brute = time(1, || {
            for p in head.positions().iter().take(sample) {
                let q = f.similarity.apply(*p);
                let best = tri
                    .iter()
                    .map(|[a, b, c]| fit::bvh::closest_on_triangle(q, *a, *b, *c).0.distance(q))
                    .fold(f32::INFINITY, f32::min);
                std::hint::black_box(best);
            }
        });
        let brute_all = brute.as_secs_f64() * head.vertex_count() as f64 / sample as f64;
        println!(
            "head of {tris} triangles, {} vertices: automatic landmarks {:.0} ms; fit from landmarks {:.0} ms (closest points by scanning every template triangle: {:.0} ms, {:.0}×); total {:.0} ms",
            head.vertex_count(),
            ms(auto),
            ms(fitted),
            brute_all * 1e3,
            brute_all / fitted.as_secs_f64(),
            ms(auto + fitted)
        );
        let floor = time(3, || {
            let v = vec![[0.25f32, 0.5]; 4096 * 4096];
            std::hint::black_box(v);
        });
        println!(
            "  correspondence map 4096²: {:.0} ms (writing a 4096² map of UVs with no work: {:.0} ms, {:.1}×)",
            ms(corr),
            ms(floor),
            corr.as_secs_f64() / floor.as_secs_f64()
        );
    }
}
