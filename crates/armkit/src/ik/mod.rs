//! ik (placeholder: being written).
