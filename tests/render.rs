//! End-to-end tests: render (to be written).
