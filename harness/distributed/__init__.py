"""Where the harness's jobs run: in this process one after another, or as tasks on Dask (an embedded
cluster on this machine, or an existing one at --scheduler). Commands build their jobs as Tasks and hand
them to an Executor; nothing else in the harness knows which one runs them."""
