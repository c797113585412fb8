// placeholder: record and replay (in progress)
