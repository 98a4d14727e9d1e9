"""Videos to programs, the paper's Table 2: episodes of an activity data set reduced once
to small frames and class shares (`cache`, `data`), the split of homes and agents
(`splits`), step recognition in 2-second clips (`clips`, over the features of the frame CNN
trained here, `framecnn`), the video -> program seq2seq (`video2prog`), training every
model per seed (`table`), scoring (`eval`) and the markdown section (`report`)."""
