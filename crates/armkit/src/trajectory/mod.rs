//! trajectory (placeholder: being written).
