#![no_main]
//! Fuzzes the regions file (`RegionSet`, read by `irsig-stats` and `irsig-report`): no
//! panic, errors inside the input, and an accepted file validates and writes back to RON
//! that reads to the same regions.

#[path = "radtran_common.rs"]
mod common;

use irsig_formats::canonical;
use irsig_model::RegionSet;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Some(set) = common::check(data, canonical::from_ron::<RegionSet>) {
        set.validate()
            .expect("an accepted regions file keeps the rules");
        let text = canonical::to_ron(&set).expect("accepted regions write");
        let again: RegionSet = canonical::from_ron("again", &text).expect("written regions read");
        assert_eq!(set, again);
    }
});
