//! Writes one of the tolerance checks' generated scenes (`irsig_tracer::testing::
//! generated_scene`, the scenes of `tests/guarantee.rs`) in the tools' own formats, so
//! that `irsig-trace` can pilot and render it: `DIR/scene.raw` (binary raw scene),
//! `DIR/materials.ron` and `DIR/view.ron`. Its sky is a vacuum's uniform 25 W m⁻² sr⁻¹
//! over the whole spectrum: trace it with `--atmosphere none --sky-radiance 25 --band
//! total`. `scripts/bench/tolerance-cost.sh` uses it.
//!
//!     cargo run --release -p irsig-tracer --example generated_scene -- SEED VIEW DIR
//!
//! VIEW is 0 (a low camera along the ground) or 1 (a mast).

use std::path::PathBuf;

use irsig_formats::canonical::{binary, to_ron};
use irsig_tracer::testing::generated_scene;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [seed, view, dir] = args.as_slice() else {
        return Err("usage: generated_scene SEED VIEW DIR (VIEW 0: low, 1: mast)".into());
    };
    let seed: u64 = seed
        .parse()
        .map_err(|e| format!("SEED `{seed}`: expected a whole number: {e}"))?;
    let view: usize = match view.as_str() {
        "0" => 0,
        "1" => 1,
        _ => return Err(format!("VIEW `{view}`: expected 0 (low) or 1 (mast)").into()),
    };
    let dir = PathBuf::from(dir);
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let (scene, materials, view) = generated_scene(seed, view);
    let mut raw = Vec::new();
    binary::write(&scene, &mut raw)?;
    for (name, bytes) in [
        ("scene.raw", raw),
        ("materials.ron", to_ron(&materials)?.into_bytes()),
        ("view.ron", to_ron(&view)?.into_bytes()),
    ] {
        let path = dir.join(name);
        std::fs::write(&path, bytes).map_err(|e| format!("{}: {e}", path.display()))?;
    }
    Ok(())
}
