//! The library's inputs end to end: every mesh format (fixtures, round trips, bad input, random
//! bytes), the real anatomy folder against an independent reader's figures, and segmentation
//! label volumes; and the app's layers (`architecture.rs`: every import against the table of
//! ARCHITECTURE.md). One test binary, one file per concern.

mod anatomy;
mod architecture;
mod formats;
mod volume_surfaces_exact;
mod volumes;
