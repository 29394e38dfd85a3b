"""What studies cost: ``bbb plan`` against measured runs and stores, the scaling model, and
measurements made before a study (mechanisms)."""
