//! Writes one of the tolerance checks' generated scenes (`irsig_tracer::testing::
//! generated_scene`, the scenes of `tests/guarantee.rs`) in the tools' own formats, so
//! that `irsig-trace` can pilot and render it: `DIR/scene.raw` (binary raw scene),
//! `DIR/materials.ron` and `DIR/view.ron`. Its sky is a vacuum's uniform 25 W m⁻² sr⁻¹
//! over the whole spectrum: trace it with `--atmosphere none --sky-radiance 25 --band
//! total`. `scripts/bench/tolerance-cost.sh` uses it.
//!
//!     cargo run --release -p irsig-tracer --example generated_scene -- SEED VIEW DIR [KIND]
//!
//! VIEW is 0 (a low camera) or 1 (from above: a mast, or a room's top corner); KIND is
//! `open` (the default), `terrain`, `mirrors` or `interior` (`SceneKind`).

use std::path::PathBuf;

use irsig_formats::canonical::{binary, to_ron};
use irsig_tracer::testing::{SceneKind, generated_scene_of};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let usage = "usage: generated_scene SEED VIEW DIR [KIND] (VIEW 0: low, 1: from above; \
                 KIND open, terrain, mirrors or interior)";
    let (seed, view, dir, kind) = match args.as_slice() {
        [seed, view, dir] => (seed, view, dir, SceneKind::Open),
        [seed, view, dir, kind] => {
            let kind = SceneKind::from_name(kind).ok_or_else(|| {
                format!("KIND `{kind}`: expected open, terrain, mirrors or interior")
            })?;
            (seed, view, dir, kind)
        }
        _ => return Err(usage.into()),
    };
    let seed: u64 = seed
        .parse()
        .map_err(|e| format!("SEED `{seed}`: expected a whole number: {e}"))?;
    let view: usize = match view.as_str() {
        "0" => 0,
        "1" => 1,
        _ => return Err(format!("VIEW `{view}`: expected 0 (low) or 1 (from above)").into()),
    };
    let dir = PathBuf::from(dir);
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let (scene, materials, view) = generated_scene_of(kind, seed, view);
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
