"""The evaluation of description -> program models: splits (`splits`), per-example scores
(`scores`), baselines that learn nothing (`baselines`) and the rule parser's upper bound
(`rules`), one run per data set, split and seed (`experiment`), mean ± sd over seeds with
bootstrap intervals (`summary`), the markdown tables (`report`), the paper's Table 3 rows
(`paper_table`), and the title -> program benchmark (`titles`)."""
