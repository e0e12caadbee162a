//! What a test needs from the machine beyond `cargo test` itself: a GPU adapter (lavapipe does),
//! the anatomy data folder, the Khronos glTF validator.
//!
//! A test that finds one of them missing calls [`skip`] and returns. On a developer's machine
//! that prints `skipped: <why>` and the test passes; where the resource is required (CI sets
//! `CUTAWAY_REQUIRE_GPU=1`, `CUTAWAY_REQUIRE_DATA=1` and `CUTAWAY_REQUIRE_VALIDATOR=1`) it
//! panics, so a missing resource fails the test instead of passing it unseen (libtest shows no
//! output of a passing test). Every test that can skip goes through here, in every crate.

use std::fmt::Display;

/// A resource some tests need.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Resource {
    /// A wgpu adapter (Mesa's lavapipe with `WGPU_BACKEND=vulkan` will do).
    Gpu,
    /// The anatomy data folder (`CUTAWAY_ANATOMY`, else `shared/anatomy` beside the workspace).
    Data,
    /// The Khronos glTF validator (`CUTAWAY_GLTF_VALIDATOR`, and node to run it).
    Validator,
}

impl Resource {
    /// The variable that, set to `1`, makes a missing resource fail the test.
    pub fn variable(self) -> &'static str {
        match self {
            Resource::Gpu => "CUTAWAY_REQUIRE_GPU",
            Resource::Data => "CUTAWAY_REQUIRE_DATA",
            Resource::Validator => "CUTAWAY_REQUIRE_VALIDATOR",
        }
    }

    /// Whether this run requires the resource (its variable is `1`).
    pub fn required(self) -> bool {
        std::env::var(self.variable()).is_ok_and(|v| v.trim() == "1")
    }
}

/// Call when `resource` is missing, then return from the test (or leave out the part that needs
/// it): prints `skipped: <why>`, or panics with `why` when the run requires the resource.
#[track_caller]
pub fn skip(resource: Resource, why: impl Display) {
    skip_or_fail(resource, resource.required(), &why);
}

#[track_caller]
fn skip_or_fail(resource: Resource, required: bool, why: &dyn Display) {
    if required {
        panic!(
            "{why} ({}=1: this run requires it, so the test fails instead of skipping)",
            resource.variable()
        );
    }
    println!("skipped: {why}");
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    #[should_panic(expected = "CUTAWAY_REQUIRE_DATA=1")]
    fn a_required_resource_that_is_missing_fails_the_test() {
        skip_or_fail(Resource::Data, true, &"no anatomy folder");
    }

    #[test]
    fn a_resource_not_required_is_skipped() {
        skip_or_fail(Resource::Gpu, false, &"no adapter");
    }

    #[test]
    fn each_resource_has_its_own_variable() {
        let names = [Resource::Gpu, Resource::Data, Resource::Validator].map(Resource::variable);
        assert_eq!(
            names,
            [
                "CUTAWAY_REQUIRE_GPU",
                "CUTAWAY_REQUIRE_DATA",
                "CUTAWAY_REQUIRE_VALIDATOR"
            ]
        );
    }
}
