//! End-to-end tests: extrude (to be written).
