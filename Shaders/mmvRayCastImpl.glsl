    // Multi-material shading: integrate the segment ending at this sample.
    if (!g_skip)
    {
      mmvValueType mmv_value = mmvValue(g_dataPos);
      if (mmv_hasPrevious)
      {
        mmvIntegrateSegment(mmv_previousPos, mmv_previousValue, g_dataPos, mmv_value);
      }
      mmv_previousPos = g_dataPos;
      mmv_previousValue = mmv_value;
      mmv_hasPrevious = true;
    }
    else
    {
      mmv_hasPrevious = false;
    }
