  // Multi-material shading: the last partial segment, from the last sample to
  // where the ray leaves the volume or meets opaque geometry.
  if (mmv_hasPrevious && g_fragColor.a <= g_opacityThreshold)
  {
    vec3 step = g_dirStep;
    vec3 boundary = mix(in_texMin[0], in_texMax[0], greaterThan(step, vec3(0.0)));
    vec3 axisFraction = vec3(1.0);
    for (int i = 0; i < 3; ++i)
    {
      if (step[i] != 0.0)
      {
        axisFraction[i] = (boundary[i] - mmv_previousPos[i]) / step[i];
      }
    }
    float fraction = min(min(axisFraction.x, axisFraction.y), axisFraction.z);
    fraction = min(fraction, dot(g_terminatePos - mmv_previousPos, step) / dot(step, step));
    fraction = clamp(fraction, 0.0, 1.0);
    if (fraction > 1e-4)
    {
      vec3 exitPos = mmv_previousPos + fraction * step;
      mmvIntegrateSegment(mmv_previousPos, mmv_previousValue, exitPos, mmvValue(exitPos));
    }
  }
  // A valid premultiplied colour (rgb <= alpha), what compositors assume:
  // highlights above 1 would otherwise add up past 1 where sort-last
  // compositing (MPI ranks) blends several pieces, and wrap around in 8 bits.
  g_fragColor.a = clamp(g_fragColor.a, 0.0, 1.0);
  g_fragColor.rgb = clamp(g_fragColor.rgb, vec3(0.0), vec3(g_fragColor.a));
