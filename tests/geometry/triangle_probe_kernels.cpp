// Placeholder: being written (per-level probe kernels for the triangle tests).
