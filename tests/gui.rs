//! End-to-end tests: gui (to be written).
