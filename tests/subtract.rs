//! End-to-end tests: subtract (to be written).
