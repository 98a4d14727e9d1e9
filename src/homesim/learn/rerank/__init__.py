"""Programs from descriptions by retrieval and reranking: the learned reranker
(`reranker`: start there), the bank and query it reads (`base`), candidate edits
(`candidates`, `median`), the scorer (`trees`), the editors of its choice (`insertion`,
`deletion`, learned without a leak: `folds`, `editors`), the lexicon of what a text names
(`lexicon`), retrieve-and-edit (`retrieve`), and the program writer built on it
(`program_writer`)."""
