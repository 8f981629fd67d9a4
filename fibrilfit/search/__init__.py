"""Searching for packings on top of the pipeline and the sweep's executors: restarts of one model
(P(fit) with its Wilson interval, the best layout) and the minimal-linker map."""
