//! redundancy (placeholder: being written).
