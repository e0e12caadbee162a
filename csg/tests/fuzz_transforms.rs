//! The stable runner of the fuzz target for random cutter transforms (`csg/fuzz/`): the same
//! body, [`csg::cutcheck::run_transform_case`], driven by proptest over random byte strings, so
//! `cargo test` exercises it on every CI run. Cases that the fuzzer finds become named tests
//! below (their bytes inline).
//!
//! More cases: `PROPTEST_CASES=5000 PROPTEST_RNG_SEED=<n> cargo test -p csg --test
//! fuzz_transforms`.

use csg::cutcheck::{CaseOutcome, run_transform_case};
use proptest::prelude::*;

fn config() -> ProptestConfig {
    let mut c = ProptestConfig::default();
    if std::env::var_os("PROPTEST_CASES").is_none() {
        c.cases = 96;
    }
    if std::env::var_os("PROPTEST_RNG_SEED").is_none() {
        c.rng_seed = proptest::test_runner::RngSeed::Fixed(0x0f0f_2026);
    }
    c
}

proptest! {
    #![proptest_config(config())]

    /// Arbitrary bytes: every target, cutter shape, placement and snap grid the decoder covers.
    #[test]
    fn random_cutter_transforms_keep_the_contract(data in prop::collection::vec(any::<u8>(), 0..24)) {
        run_transform_case(&data).map_err(TestCaseError::fail)?;
    }
}

/// The decoder's edge cases: empty input (icosphere target, a unit box cutter, smallest scale,
/// at the far corner, unsnapped), all-ones bytes (largest scale and shift, snapped).
#[test]
fn degenerate_inputs_decode_and_cut() {
    assert!(matches!(
        run_transform_case(&[]),
        Ok(CaseOutcome::Checked { .. })
    ));
    let all = [0xffu8; 24];
    assert!(run_transform_case(&all).is_ok());
}

/// The decoder is not vacuous: most random inputs really cut (contours), few are refused.
#[test]
fn random_inputs_mostly_cut() {
    let mut s = 0x9e37_79b9_7f4a_7c15u64;
    let (mut cut, mut refused, n) = (0, 0, 300);
    for _ in 0..n {
        let data: Vec<u8> = (0..24)
            .map(|_| {
                s ^= s << 13;
                s ^= s >> 7;
                s ^= s << 17;
                (s >> 56) as u8
            })
            .collect();
        match run_transform_case(&data) {
            Ok(CaseOutcome::Checked { contours }) if contours > 0 => cut += 1,
            Ok(CaseOutcome::Checked { .. }) => {}
            Ok(CaseOutcome::Refused) => refused += 1,
            Err(e) => panic!("{data:?}: {e}"),
        }
    }
    eprintln!("{n} inputs: {cut} cut, {refused} refused");
    assert!(cut * 2 > n, "only {cut} of {n} inputs cut the target");
    assert!(refused * 5 < n, "{refused} of {n} inputs refused");
}

/// A cutter box snapped to the unit grid against a box target whose faces lie on that grid:
/// the cutter (x from 0 to 16, y and z ±8) shares four face planes with the target (±8) and has
/// target vertices on its edges; the tie-break resolves it (not refused).
#[test]
fn snapped_box_through_box_target() {
    // target 2 (box ±8), cutter 0 (box ±1), no rotation (zero axis → z, angle 0).
    let mut data = vec![2u8, 0];
    data.extend([0x80, 0x7f, 0x80, 0x7f, 0x80, 0x7f]); // axis ≈ 0
    data.extend([0, 0]); // angle 0
    data.extend([0x93, 0xe2, 0x93, 0xe2, 0x93, 0xe2]); // scale ≈ 8
    data.extend([0x54, 0xd5, 0xff, 0x7f, 0xff, 0x7f]); // shift ≈ (8, 0, 0)
    data.push(0b11); // snapped to step 1
    assert!(matches!(
        run_transform_case(&data),
        Ok(CaseOutcome::Checked { contours }) if contours > 0
    ));
}
