//! Prints the height and depth of the default head along a few columns (for documenting
//! its UV layout): `cargo run -p agesim --example head_landmarks`.
fn main() {
    for u in [0.5f32, 0.44, 0.25, 0.0] {
        println!("u = {u}");
        let vs: Vec<f32> = (0..=50).map(|j| j as f32 / 50.0).collect();
        for (v, p) in vs.iter().zip(agesim::assets::head::head_column(u, &vs)) {
            println!("  v {v:.2}: x {:+.3} y {:+.3} z {:+.3}", p.x, p.y, p.z);
        }
    }
}
