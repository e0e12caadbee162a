//! End-to-end tests: scalpel (to be written).
