// Test-only auto-start component of the GUI tests: adds a QAction named
// "mmvPanelProbe" to the main window. A QtTesting script activates it to
// record the Properties panel as the user sees it: the property widgets of
// the display section that are shown (every ancestor visible), the gear's
// state, and screen shots of the panel scrolled page by page through all
// its groups. Written to $MMV_PANEL_PROBE (a folder): panel.txt and
// panel-<record>-<page>.png.
#ifndef pqMMVPanelProbe_h
#define pqMMVPanelProbe_h

#include <QObject>

class pqMMVPanelProbe : public QObject
{
  Q_OBJECT
public:
  explicit pqMMVPanelProbe(QObject* parent = nullptr);
  ~pqMMVPanelProbe() override;

  void onStartup();
  void onShutdown();

private:
  void installAction();
  void record();
  int Records = 0;
};

#endif
