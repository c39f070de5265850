  // Multi-material shading: the first segment starts where the ray enters
  // the volume, before the jitter offset of the first sample.
  mmvBeginBlock();
  mmv_previousPos = g_dataPos - g_rayJitter;
  mmv_previousValue = mmvValue(mmv_previousPos);
  mmv_hasPrevious = true;
