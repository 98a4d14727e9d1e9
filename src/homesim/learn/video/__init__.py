"""Videos to programs, the paper's Table 2: episodes of an activity data set reduced once
to small frames, class maps and joints (`cache`) and written into one memory-mapped frame
store (`store`, `data`) with the split its folders declare (`splits`); frame encoders
trained here on RGB and on class maps (`framecnn`), a segmentation network (`segment`)
and a pose network (`pose`), whose features of every frame are computed once; step
recognition in 2-second clips (`clips`: TRN over those features); the video -> program
seq2seq (`video2prog`); training every stage, resumable per epoch (`fit`, `table`);
scoring with bootstrap intervals (`eval`) and the markdown section (`report`)."""
