#![no_main]
//! Fuzzes every canonical RON reader: the first byte picks the type (object, scene, raw
//! scene, material library, atmosphere, view, pipeline), the rest is the text. A value
//! that reads and validates must write back, and the writing must read again to the same
//! text (bit-exact numbers).

#[path = "mesh_common.rs"]
#[allow(dead_code)] // each target uses only some of the checks
mod mesh_common;

use irsig_formats::canonical::{self, Canonical};
use irsig_model::{Atmosphere, MaterialLibrary, Object, RawScene, Scene, View};
use libfuzzer_sys::fuzz_target;

fn check<T: Canonical>(data: &[u8]) {
    match canonical::from_ron_bytes::<T>("fuzz.ron", data) {
        Ok(value) => {
            let text = canonical::to_ron(&value).expect("a valid value writes as RON");
            let again: T = canonical::from_ron("rewritten.ron", &text)
                .unwrap_or_else(|e| panic!("the writer's RON does not read back: {e}\n{text}"));
            assert_eq!(canonical::to_ron(&again).expect("writes again"), text);
        }
        Err(e) => mesh_common::check_error(&e, "fuzz.ron", data),
    }
}

fuzz_target!(|data: &[u8]| {
    let Some((&which, rest)) = data.split_first() else {
        return;
    };
    match which % 7 {
        0 => check::<Object>(rest),
        1 => check::<Scene>(rest),
        2 => check::<RawScene>(rest),
        3 => check::<MaterialLibrary>(rest),
        4 => check::<Atmosphere>(rest),
        5 => check::<View>(rest),
        _ => {
            if let Ok(text) = std::str::from_utf8(rest) {
                let _ = irsig_pipeline::Pipeline::parse(
                    "fuzz.ron",
                    text,
                    std::path::Path::new("/nonexistent-irsig-fuzz"),
                );
            }
        }
    }
});
