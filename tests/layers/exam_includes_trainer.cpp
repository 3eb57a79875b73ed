// Must not compile: the exam (cases, scoring, reports, records) is below the trainer, which shows
// it in the window; the scorer runs headless without any screen.
#include "exam/scorer.hpp"
#include "trainer/trainer.hpp"
