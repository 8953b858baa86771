// placeholder: filled in by the radio-link work (issue 2)
