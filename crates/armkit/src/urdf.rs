//! URDF loading (issue 3). Placeholder: being written.
