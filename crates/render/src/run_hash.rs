//! The run a frame belongs to, as its EXRs name it (`irsig.run`, formats/images.md): a
//! SHA-256 of the inputs (scene bytes, materials, declared uncertainties, band, atmosphere
//! and its sky's top altitude), the view and the settings the pixels are rendered with;
//! not the outputs, the tile, the thread count or the digital-count flags, which change no
//! pixel. A frame traced whole and every tile of it name the same run, so that tiles of
//! other runs never merge.

use irsig_model::View;
use irsig_tracer::TraceOptions;
use sha2::{Digest, Sha256};

use crate::settings::Settings;

/// The first words of every run hash: a new rule for what the hash covers gets a new
/// version, so that tiles of the two rules never merge.
const RUN_HASH_VERSION: &[u8] = b"irsig-trace run 1\n";

/// The hash of a run's inputs, fed in a fixed order as they are read.
#[derive(Debug, Clone)]
pub struct RunHash(Sha256);

impl Default for RunHash {
    fn default() -> Self {
        let mut h = Sha256::new();
        h.update(RUN_HASH_VERSION);
        Self(h)
    }
}

impl RunHash {
    /// Feeds one named input, its length first, so that no two different sequences of
    /// inputs hash alike.
    pub fn field(&mut self, name: &str, bytes: &[u8]) {
        self.0.update(name.as_bytes());
        self.0.update((bytes.len() as u64).to_le_bytes());
        self.0.update(bytes);
    }

    /// The run of one frame: these inputs, `view` and `settings`, as `sha256:HEX`.
    #[must_use]
    pub fn frame(&self, view: &View, settings: &Settings) -> String {
        let sub_bands = settings.sub_bands;
        let mut h = self.clone();
        h.field("view", format!("{view:?}").as_bytes());
        let options = TraceOptions {
            truth: true,
            ..settings.options
        };
        let mut text = format!("{options:?} {:?} {:?}", settings.kind, settings.path_terms);
        if !sub_bands.is_band() {
            text.push_str(&format!(" sub-bands {sub_bands}"));
        }
        if let Some(r) = &settings.refinement {
            text.push_str(&format!(" {r:?}"));
        }
        // The sun's settings only where a decision set them (a night's hash as before).
        if !settings.sun_lit {
            text.push_str(" sun off");
        }
        if let Some(n) = settings.shadow_rays {
            text.push_str(&format!(" shadow-rays {n}"));
        }
        h.field("settings", text.as_bytes());
        let digest = h.0.finalize();
        let mut hex = String::with_capacity(7 + 64);
        hex.push_str("sha256:");
        for b in digest {
            hex.push_str(&format!("{b:02x}"));
        }
        hex
    }
}
