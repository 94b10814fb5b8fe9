"""The harness: runs each engine in isolation, times and scores it, stores the rows and gates them."""
