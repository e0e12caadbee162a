//! Fuzz target: random rigid transforms, scalings and grid snaps of cutters against spheres, tori
//! and boxes (see `csg::cutcheck::run_transform_case`). A panic, an internal error, a refused
//! valid cutter or a broken identity is a finding; turn it into a named test in
//! `csg/tests/fuzz_transforms.rs` with its bytes inline.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Err(e) = csg::cutcheck::run_transform_case(data) {
        panic!("{e}");
    }
});
