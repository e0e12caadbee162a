//! End-to-end tests: anatomy (to be written).
