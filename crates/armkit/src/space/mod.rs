//! space (placeholder: being written).
